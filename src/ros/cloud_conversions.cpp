#include "adaptive_lego_loam/ros/cloud_conversions.h"

#include <sensor_msgs/point_cloud2_iterator.h>

#include "adaptive_lego_loam/io/point_fields.h"

namespace adaptive_lego_loam::ros_bridge {

Scan from_ros(const sensor_msgs::PointCloud2& msg, const std::string& source) {
  Scan scan = decode_points(packed_points(msg), source);
  scan.stamp = msg.header.stamp.toSec();
  return scan;
}

sensor_msgs::PointCloud2 to_ros(const std::vector<ScanPoint>& points,
                                const std_msgs::Header& header, bool with_ring_and_time) {
  sensor_msgs::PointCloud2 msg;
  msg.header = header;
  sensor_msgs::PointCloud2Modifier modifier(msg);
  if (with_ring_and_time) {
    modifier.setPointCloud2Fields(
        6, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z",
        1, sensor_msgs::PointField::FLOAT32, "intensity", 1, sensor_msgs::PointField::FLOAT32,
        "ring", 1, sensor_msgs::PointField::UINT16, "time", 1, sensor_msgs::PointField::FLOAT32);
  } else {
    modifier.setPointCloud2Fields(
        4, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z",
        1, sensor_msgs::PointField::FLOAT32, "intensity", 1, sensor_msgs::PointField::FLOAT32);
  }
  modifier.resize(points.size());
  msg.height = 1;
  msg.width = static_cast<uint32_t>(points.size());
  msg.is_dense = false;
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z");
  sensor_msgs::PointCloud2Iterator<float> intensity(msg, "intensity");
  for (const ScanPoint& p : points) {
    *x = p.x;
    *y = p.y;
    *z = p.z;
    *intensity = p.intensity;
    ++x, ++y, ++z, ++intensity;
  }
  if (with_ring_and_time) {
    sensor_msgs::PointCloud2Iterator<uint16_t> ring(msg, "ring");
    sensor_msgs::PointCloud2Iterator<float> time(msg, "time");
    for (const ScanPoint& p : points) {
      *ring = static_cast<uint16_t>(p.ring < 0 ? 0 : p.ring);
      *time = p.time;
      ++ring, ++time;
    }
  }
  return msg;
}

}  // namespace adaptive_lego_loam::ros_bridge
