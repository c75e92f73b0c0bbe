#pragma once
// Clouds as the drivers of spinning LiDARs publish them: each driver's fields with their names,
// types and offsets, its point step, its organisation and its ring and time conventions, written
// from one sweep of beams x columns. The layouts are the drivers' own (named at each builder);
// nothing of the drivers is needed to build them.

#include <sensor_msgs/PointCloud2.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam::test {

// One sweep as the sensor measures it: beams x columns cells, each a return or none.
struct DriverSweep {
  int beams = 0;
  int columns = 0;
  double period = 0.1;         // s
  double start_stamp = 1.7e9;  // s: the clock's time at column 0's firing
  // cells[beam * columns + column], beam 0 the lowest; nothing where no return came back.
  std::vector<std::optional<ScanPoint>> cells;

  double column_time(int column) const { return period * column / columns; }
  const std::optional<ScanPoint>& cell(int beam, int column) const {
    return cells[static_cast<std::size_t>(beam) * columns + column];
  }
  int returns() const {
    int count = 0;
    for (const auto& cell : cells)
      count += cell.has_value();
    return count;
  }
};

// Beams at `elevations_deg` (ascending), a wall 5 to 25 m away whose range changes with the
// column, and no return on every seventh cell. Point times are their columns' times.
inline DriverSweep example_sweep(const std::vector<double>& elevations_deg, int columns,
                                 double period = 0.1) {
  DriverSweep sweep;
  const int beams = static_cast<int>(elevations_deg.size());
  sweep.beams = beams;
  sweep.columns = columns;
  sweep.period = period;
  for (int beam = 0; beam < beams; ++beam) {
    const double elevation = elevations_deg[beam] * M_PI / 180.0;
    for (int column = 0; column < columns; ++column) {
      if ((beam * columns + column) % 7 == 3) {
        sweep.cells.emplace_back();
        continue;
      }
      // Clockwise from behind the sensor, as a Velodyne turns.
      const double azimuth = M_PI - 2.0 * M_PI * column / columns;
      const double range = 5.0 + 20.0 * column / columns + 0.1 * beam;
      ScanPoint p;
      p.x = static_cast<float>(range * std::cos(elevation) * std::cos(azimuth));
      p.y = static_cast<float>(range * std::cos(elevation) * std::sin(azimuth));
      p.z = static_cast<float>(range * std::sin(elevation));
      p.intensity = static_cast<float>((beam + column) % 200);
      p.ring = beam;
      p.time = static_cast<float>(sweep.column_time(column));
      sweep.cells.emplace_back(p);
    }
  }
  return sweep;
}

// The same with beams evenly from `lowest_deg` to `highest_deg`.
inline DriverSweep example_sweep(int beams, int columns, double lowest_deg, double highest_deg,
                                 double period = 0.1) {
  std::vector<double> elevations;
  for (int beam = 0; beam < beams; ++beam)
    elevations.push_back(lowest_deg + (highest_deg - lowest_deg) * beam / std::max(beams - 1, 1));
  return example_sweep(elevations, columns, period);
}

// A cloud's fields and records, filled one value at a time.
class CloudWriter {
 public:
  CloudWriter(uint32_t point_step, uint32_t width, uint32_t height) {
    msg_.point_step = point_step;
    msg_.width = width;
    msg_.height = height;
    msg_.row_step = point_step * width;
    msg_.is_bigendian = false;
    msg_.is_dense = false;
    msg_.data.assign(std::size_t{msg_.row_step} * height, 0);
  }
  void field(const std::string& name, uint32_t offset, uint8_t datatype) {
    sensor_msgs::PointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = datatype;
    f.count = 1;
    msg_.fields.push_back(f);
  }
  // Writes `value` at `offset` into the record of point `index` (row-major).
  template <typename T>
  void put(std::size_t index, uint32_t offset, T value) {
    std::memcpy(msg_.data.data() + index * msg_.point_step + offset, &value, sizeof(T));
  }
  sensor_msgs::PointCloud2 finish(double stamp, const std::string& frame) {
    msg_.header.stamp.fromSec(stamp);
    msg_.header.frame_id = frame;
    return msg_;
  }

 private:
  sensor_msgs::PointCloud2 msg_;
};

using sensor_msgs::PointField;

// ouster-ros (ouster_ros::Point, include/ouster_ros/os_point.h; PCL's layout of the struct
// PCL_ADD_POINT4D; float intensity; uint32_t t; uint16_t reflectivity; uint16_t ring (uint8_t
// before ouster-ros 0.9); uint16_t ambient; uint32_t range, 16-byte aligned): x y z at 0 4 8,
// intensity 16, t 20 (ns since the frame's first column), reflectivity 24, ring 26, ambient 28,
// range 32 (mm), point step 48. Organised: height = beams with row 0 the top beam (ring = row),
// width = columns, x = y = z = 0 and range 0 where no return came back. `destaggered`: row u is
// shifted by pixel_shift_by_row[u] (here 12 - u % 4 * 6 columns, as on an OS1 at 1024 columns),
// each point keeping its own column's time; staggered: cloud column v is measurement column v.
inline sensor_msgs::PointCloud2 ouster_ros_cloud(const DriverSweep& sweep, bool ring_uint16,
                                                 bool destaggered) {
  CloudWriter cloud(48, sweep.columns, sweep.beams);
  cloud.field("x", 0, PointField::FLOAT32);
  cloud.field("y", 4, PointField::FLOAT32);
  cloud.field("z", 8, PointField::FLOAT32);
  cloud.field("intensity", 16, PointField::FLOAT32);
  cloud.field("t", 20, PointField::UINT32);
  cloud.field("reflectivity", 24, PointField::UINT16);
  cloud.field("ring", 26, ring_uint16 ? PointField::UINT16 : PointField::UINT8);
  cloud.field("ambient", 28, PointField::UINT16);
  cloud.field("range", 32, PointField::UINT32);
  for (int row = 0; row < sweep.beams; ++row) {
    const int beam = sweep.beams - 1 - row;
    const int shift = destaggered ? 12 - row % 4 * 6 : 0;
    for (int column = 0; column < sweep.columns; ++column) {
      const int cloud_column = (column + shift + sweep.columns) % sweep.columns;
      const std::size_t index = std::size_t(row) * sweep.columns + cloud_column;
      const auto& cell = sweep.cell(beam, column);
      cloud.put<uint32_t>(index, 20,
                          static_cast<uint32_t>(std::llround(sweep.column_time(column) * 1e9)));
      if (ring_uint16) {
        cloud.put<uint16_t>(index, 26, static_cast<uint16_t>(row));
      } else {
        cloud.put<uint8_t>(index, 26, static_cast<uint8_t>(row));
      }
      if (!cell) continue;
      cloud.put<float>(index, 0, cell->x);
      cloud.put<float>(index, 4, cell->y);
      cloud.put<float>(index, 8, cell->z);
      cloud.put<float>(index, 16, cell->intensity);
      cloud.put<uint16_t>(index, 24, 100);
      cloud.put<uint16_t>(index, 28, 7);
      const double range = std::sqrt(cell->x * cell->x + cell->y * cell->y + cell->z * cell->z);
      cloud.put<uint32_t>(index, 32, static_cast<uint32_t>(range * 1000.0));
    }
  }
  return cloud.finish(sweep.start_stamp, "os_sensor");
}

// The legacy OS1 driver (ouster_example's first ouster_ros, point_os1.h: PCL_ADD_POINT4D; float t;
// uint16_t reflectivity; uint16_t intensity; uint8_t ring): x y z at 0 4 8, t 16 (float32, the
// column's share of the sweep, os1_ros.cpp's (column stamp - scan start) / scan duration),
// reflectivity 20, intensity 22, ring 24 (the pixel row, 0 the top beam), point step 32.
// Unorganised (height 1), column after column, every pixel pushed (0 0 0 without a return).
inline sensor_msgs::PointCloud2 legacy_os1_cloud(const DriverSweep& sweep) {
  CloudWriter cloud(32, sweep.columns * sweep.beams, 1);
  cloud.field("x", 0, PointField::FLOAT32);
  cloud.field("y", 4, PointField::FLOAT32);
  cloud.field("z", 8, PointField::FLOAT32);
  cloud.field("t", 16, PointField::FLOAT32);
  cloud.field("reflectivity", 20, PointField::UINT16);
  cloud.field("intensity", 22, PointField::UINT16);
  cloud.field("ring", 24, PointField::UINT8);
  std::size_t index = 0;
  for (int column = 0; column < sweep.columns; ++column) {
    for (int row = 0; row < sweep.beams; ++row, ++index) {
      const auto& cell = sweep.cell(sweep.beams - 1 - row, column);
      cloud.put<float>(index, 16, static_cast<float>(column) / sweep.columns);
      cloud.put<uint8_t>(index, 24, static_cast<uint8_t>(row));
      if (!cell) continue;
      cloud.put<float>(index, 0, cell->x);
      cloud.put<float>(index, 4, cell->y);
      cloud.put<float>(index, 8, cell->z);
      cloud.put<uint16_t>(index, 22, static_cast<uint16_t>(cell->intensity));
    }
  }
  return cloud.finish(sweep.start_stamp, "os1_lidar");
}

// Hesai's HesaiLidar_General_ROS (PandarGeneralRaw/include/pandarGeneral/point_types.h:
// PCL_ADD_POINT4D; float intensity; double timestamp; uint16_t ring, 16-byte aligned): x y z at
// 0 4 8, intensity 16, timestamp 24 (float64, absolute seconds), ring 32, point step 48.
// Unorganised (height 1), in firing order, points without a return left out; ring = the
// channel's index in the packet, which the Pandar XT32 numbers from its top beam
// (`top_down`) and the Pandar QT64 from its bottom beam (the SDK's pandarXT_elev_angle_map and
// pandarQT_elev_angle_map).
inline sensor_msgs::PointCloud2 hesai_cloud(const DriverSweep& sweep, bool top_down) {
  CloudWriter cloud(48, sweep.returns(), 1);
  cloud.field("x", 0, PointField::FLOAT32);
  cloud.field("y", 4, PointField::FLOAT32);
  cloud.field("z", 8, PointField::FLOAT32);
  cloud.field("intensity", 16, PointField::FLOAT32);
  cloud.field("timestamp", 24, PointField::FLOAT64);
  cloud.field("ring", 32, PointField::UINT16);
  std::size_t index = 0;
  for (int column = 0; column < sweep.columns; ++column) {
    for (int channel = 0; channel < sweep.beams; ++channel) {
      const auto& cell = sweep.cell(top_down ? sweep.beams - 1 - channel : channel, column);
      if (!cell) continue;
      cloud.put<float>(index, 0, cell->x);
      cloud.put<float>(index, 4, cell->y);
      cloud.put<float>(index, 8, cell->z);
      cloud.put<float>(index, 16, cell->intensity);
      cloud.put<double>(index, 24, sweep.start_stamp + sweep.column_time(column));
      cloud.put<uint16_t>(index, 32, static_cast<uint16_t>(channel));
      ++index;
    }
  }
  return cloud.finish(sweep.start_stamp, "hesai_lidar");
}

// rslidar_sdk with POINT_TYPE XYZIRT (src/msg/ros_msg_translator.h, toRosMsg: the fields added
// one after the other by addPointField, without alignment): x y z intensity float32 at 0 4 8 12,
// ring uint16 at 16, timestamp float64 (absolute seconds) at 18, point step 26. Organised as the
// driver sends by default (ros_send_by_rows false): width = beams, height = columns, a firing per
// row; ring counts from the lowest beam (rs_driver's ChanAngles::genUserChan); NaN coordinates
// where no return came back (dense_points false).
inline sensor_msgs::PointCloud2 rslidar_cloud(const DriverSweep& sweep) {
  CloudWriter cloud(26, sweep.beams, sweep.columns);
  cloud.field("x", 0, PointField::FLOAT32);
  cloud.field("y", 4, PointField::FLOAT32);
  cloud.field("z", 8, PointField::FLOAT32);
  cloud.field("intensity", 12, PointField::FLOAT32);
  cloud.field("ring", 16, PointField::UINT16);
  cloud.field("timestamp", 18, PointField::FLOAT64);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::size_t index = 0;
  for (int column = 0; column < sweep.columns; ++column) {
    for (int beam = 0; beam < sweep.beams; ++beam, ++index) {
      const auto& cell = sweep.cell(beam, column);
      cloud.put<float>(index, 0, cell ? cell->x : nan);
      cloud.put<float>(index, 4, cell ? cell->y : nan);
      cloud.put<float>(index, 8, cell ? cell->z : nan);
      cloud.put<float>(index, 12, cell ? cell->intensity : 0.f);
      cloud.put<uint16_t>(index, 16, static_cast<uint16_t>(beam));
      cloud.put<double>(index, 18, sweep.start_stamp + sweep.column_time(column));
    }
  }
  return cloud.finish(sweep.start_stamp + sweep.period, "rslidar");
}

// velodyne_pointcloud's PointcloudXYZIRT (src/lib/pointcloudXYZIRT.cc: the fields of its
// DataContainerBase set one after the other by PointCloud2Modifier, without alignment): x y z
// intensity float32 at 0 4 8 12, ring uint16 at 16, time float32 at 18 (s after the sweep's
// first packet), point step 22. Unorganised, in firing order, rings from the lowest beam.
inline sensor_msgs::PointCloud2 velodyne_cloud(const DriverSweep& sweep) {
  CloudWriter cloud(22, sweep.returns(), 1);
  cloud.field("x", 0, PointField::FLOAT32);
  cloud.field("y", 4, PointField::FLOAT32);
  cloud.field("z", 8, PointField::FLOAT32);
  cloud.field("intensity", 12, PointField::FLOAT32);
  cloud.field("ring", 16, PointField::UINT16);
  cloud.field("time", 18, PointField::FLOAT32);
  std::size_t index = 0;
  for (int column = 0; column < sweep.columns; ++column) {
    for (int beam = 0; beam < sweep.beams; ++beam) {
      const auto& cell = sweep.cell(beam, column);
      if (!cell) continue;
      cloud.put<float>(index, 0, cell->x);
      cloud.put<float>(index, 4, cell->y);
      cloud.put<float>(index, 8, cell->z);
      cloud.put<float>(index, 12, cell->intensity);
      cloud.put<uint16_t>(index, 16, static_cast<uint16_t>(beam));
      cloud.put<float>(index, 18, cell->time);
      ++index;
    }
  }
  return cloud.finish(sweep.start_stamp + sweep.period, "velodyne");
}

}  // namespace adaptive_lego_loam::test
