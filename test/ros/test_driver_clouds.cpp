// Clouds as the drivers publish them (driver_clouds.h), through image_projection's conversion
// (from_ros) and through run_sequence's bag reader (open_bag_sequence): every return comes back
// with its coordinates, the driver's ring and its time within the sweep.

#include <gtest/gtest.h>

#include <rosbag/bag.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <tuple>

#include "adaptive_lego_loam/core/projection/range_image.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/bag_sequence.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "driver_clouds.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

constexpr int kBeams = 16, kColumns = 360;
constexpr double kPeriod = 0.1;

// The driver's ring number of a beam (0 the lowest).
using RingOf = std::function<int(int beam)>;
const RingOf kBottomUp = [](int beam) { return beam; };
const RingOf kTopDown = [](int beam) { return kBeams - 1 - beam; };

DriverSweep sweep() {
  return example_sweep(kBeams, kColumns, -15.0, 15.0, kPeriod);
}

// A point of a scan or a sweep, comparable.
using Entry = std::tuple<float, float, float, int, float>;

std::vector<Entry> expected_entries(const DriverSweep& sweep, const RingOf& ring_of) {
  std::vector<Entry> entries;
  for (int beam = 0; beam < sweep.beams; ++beam) {
    for (int column = 0; column < sweep.columns; ++column) {
      if (const auto& p = sweep.cell(beam, column)) {
        entries.emplace_back(p->x, p->y, p->z, ring_of(beam), p->time);
      }
    }
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}

// The scan's returns: finite points off the origin (organised drivers fill the rest with NaN or
// zeros).
std::vector<Entry> returned_entries(const Scan& scan) {
  std::vector<Entry> entries;
  for (const ScanPoint& p : scan.points) {
    if (!std::isfinite(p.x + p.y + p.z) || (p.x == 0.f && p.y == 0.f && p.z == 0.f)) continue;
    entries.emplace_back(p.x, p.y, p.z, p.ring, p.time);
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}

void expect_returns(const Scan& scan, const DriverSweep& sweep, const RingOf& ring_of) {
  EXPECT_TRUE(scan.has_ring);
  EXPECT_TRUE(scan.has_time);
  const std::vector<Entry> expected = expected_entries(sweep, ring_of);
  const std::vector<Entry> decoded = returned_entries(scan);
  ASSERT_EQ(decoded.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto& [x, y, z, ring, time] = expected[i];
    const auto& [dx, dy, dz, dring, dtime] = decoded[i];
    ASSERT_EQ(std::tie(dx, dy, dz), std::tie(x, y, z)) << "point " << i;
    ASSERT_EQ(dring, ring) << "point " << i;
    ASSERT_NEAR(dtime, time, 1e-6) << "point " << i << ": the time within the sweep";
  }
}

// The cloud as image_projection decodes it (the node passes its config's scan period).
Scan decoded(const sensor_msgs::PointCloud2& cloud) {
  return ros_bridge::from_ros(cloud, "/points", {kPeriod});
}

// The cloud written to a bag and read back as run_sequence reads bags.
Scan through_bag(const sensor_msgs::PointCloud2& cloud, const std::string& name) {
  const std::string path = temp_path(name + ".bag");
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    bag.write("/points", cloud.header.stamp, cloud);
  }
  const auto sequence = ros_bridge::open_bag_sequence(path, "", {kPeriod});
  std::optional<Scan> scan = sequence->next();
  std::filesystem::remove(path);
  if (!scan) throw std::runtime_error(path + ": no scan");
  return *scan;
}

void expect_same_points(const Scan& a, const Scan& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const ScanPoint &p = a.points[i], &q = b.points[i];
    const auto bits = [](float v) {
      uint32_t u;
      std::memcpy(&u, &v, 4);
      return u;
    };
    ASSERT_EQ(std::make_tuple(bits(p.x), bits(p.y), bits(p.z), p.ring, p.time),
              std::make_tuple(bits(q.x), bits(q.y), bits(q.z), q.ring, q.time))
        << "point " << i;
  }
  EXPECT_EQ(a.stamp, b.stamp);
}

// Decoded both ways: the returns of the sweep, and the same scan from the bag.
void expect_layout_read(const sensor_msgs::PointCloud2& cloud, const DriverSweep& sweep,
                        const RingOf& ring_of, const std::string& name) {
  const Scan scan = decoded(cloud);
  expect_returns(scan, sweep, ring_of);
  expect_same_points(through_bag(cloud, name), scan);
}

}  // namespace

TEST(DriverClouds, OusterRosWithUint8RingStaggered) {
  const DriverSweep s = sweep();
  const sensor_msgs::PointCloud2 cloud = ouster_ros_cloud(s, false, false);
  expect_layout_read(cloud, s, kTopDown, "ouster_uint8");
  // Organised: every pixel a point, zeros where nothing came back.
  EXPECT_EQ(decoded(cloud).points.size(), std::size_t{kBeams} * kColumns);
}

TEST(DriverClouds, OusterRosWithUint16RingDestaggered) {
  const DriverSweep s = sweep();
  expect_layout_read(ouster_ros_cloud(s, true, true), s, kTopDown, "ouster_uint16");
}

TEST(DriverClouds, LegacyOs1TimeIsAShareOfTheSweep) {
  const DriverSweep s = sweep();
  const sensor_msgs::PointCloud2 cloud = legacy_os1_cloud(s);
  expect_layout_read(cloud, s, kTopDown, "legacy_os1");
  // Without the sweep's period the share cannot become seconds: the scan has no time field (and
  // de-skewing falls back to the azimuth) rather than times ten times too long.
  const Scan without_period = ros_bridge::from_ros(cloud, "/os1_node/points");
  EXPECT_FALSE(without_period.has_time);
  EXPECT_TRUE(without_period.has_ring);
}

TEST(DriverClouds, HesaiXt32AbsoluteTimestampsBecomeOffsets) {
  const DriverSweep s = sweep();
  const sensor_msgs::PointCloud2 cloud = hesai_cloud(s, true);
  expect_layout_read(cloud, s, kTopDown, "hesai_xt32");
  // Unorganised, returns only.
  EXPECT_EQ(decoded(cloud).points.size(), std::size_t(s.returns()));
}

TEST(DriverClouds, HesaiQt64NumbersRingsFromTheBottom) {
  const DriverSweep s = sweep();
  expect_layout_read(hesai_cloud(s, false), s, kBottomUp, "hesai_qt64");
}

TEST(DriverClouds, RslidarXyzirtUnalignedTimestampsAndNanPadding) {
  const DriverSweep s = sweep();
  const sensor_msgs::PointCloud2 cloud = rslidar_cloud(s);
  ASSERT_EQ(cloud.point_step, 26u);
  expect_layout_read(cloud, s, kBottomUp, "rslidar");
  const Scan scan = decoded(cloud);
  EXPECT_EQ(scan.points.size(), std::size_t{kBeams} * kColumns);
}

TEST(DriverClouds, VelodynePointcloudXyzirt) {
  const DriverSweep s = sweep();
  expect_layout_read(velodyne_cloud(s), s, kBottomUp, "velodyne");
}

// A clock's stamps keep their microseconds: 1.7e9 s in a float are 128 s apart.
TEST(DriverClouds, AbsoluteStampsKeepMicroseconds) {
  DriverSweep s = sweep();
  s.start_stamp = 1712345678.123456;
  const Scan scan = decoded(hesai_cloud(s, true));
  float latest = 0.f;
  for (const ScanPoint& p : scan.points)
    latest = std::max(latest, p.time);
  EXPECT_NEAR(latest, s.column_time(kColumns - 1), 1e-6);
}

TEST(DriverClouds, AFieldOfAnUnexpectedTypeNamesTheTypeFoundAndExpected) {
  sensor_msgs::PointCloud2 cloud = ouster_ros_cloud(sweep(), true, false);
  for (auto& field : cloud.fields) {
    if (field.name == "ring") field.datatype = sensor_msgs::PointField::FLOAT32;
  }
  const std::string error = error_of([&] { decoded(cloud); });
  EXPECT_NE(error.find("/points: field 'ring' has type float32; expected an integer type"),
            std::string::npos)
      << error;
}

TEST(DriverClouds, AMissingCoordinateNamesTheFieldsPresent) {
  sensor_msgs::PointCloud2 cloud = hesai_cloud(sweep(), true);
  cloud.fields.erase(cloud.fields.begin() + 2);  // z
  const std::string error = error_of([&] { decoded(cloud); });
  EXPECT_NE(error.find("/points: missing field z; fields present: x y intensity timestamp ring"),
            std::string::npos)
      << error;
}

namespace {

// The share of a driver's returns that the shipped config puts in the row of the beam they came
// from (the beam's elevation in the config).
double share_in_beam_row(const std::string& config_file,
                         const std::function<sensor_msgs::PointCloud2(const DriverSweep&)>& cloud) {
  const SensorParams sensor = load_config(std::string(CONFIG_DIR) + "/" + config_file).sensor;
  const DriverSweep sweep = example_sweep(sensor.beam_angles_deg, 360, sensor.scan_period);
  const Scan scan = ros_bridge::from_ros(cloud(sweep), "/points", {sensor.scan_period});
  RangeImage image;
  RangeProjector(sensor).project(scan, image);
  int right = 0;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (!image.occupied(cell)) continue;
    const ScanPoint& p = image.point(cell);
    const double elevation = std::atan2(p.z, std::hypot(p.x, p.y)) * 180.0 / M_PI;
    right += std::abs(elevation - sensor.beam_angles_deg[image.row_of(cell)]) < 1e-3;
  }
  return static_cast<double>(right) / sweep.returns();
}

}  // namespace

// Each shipped config reads the ring field as its driver numbers the beams (ouster-ros and the
// XT32 from the top, the QT64 and rs_driver from the bottom): every return in its beam's row.
TEST(DriverClouds, ShippedConfigsReadTheirDriversRings) {
  const auto ouster = [](const DriverSweep& s) { return ouster_ros_cloud(s, true, true); };
  for (const char* config : {"os0_64.yaml", "os1_64.yaml", "os1_128.yaml", "os2_128.yaml"}) {
    EXPECT_EQ(share_in_beam_row(config, ouster), 1.0) << config;
  }
  EXPECT_EQ(share_in_beam_row("pandar_xt32.yaml",
                              [](const DriverSweep& s) { return hesai_cloud(s, true); }),
            1.0);
  EXPECT_EQ(share_in_beam_row("pandar_qt64.yaml",
                              [](const DriverSweep& s) { return hesai_cloud(s, false); }),
            1.0);
  EXPECT_EQ(share_in_beam_row("rs_helios_32.yaml", rslidar_cloud), 1.0);
  EXPECT_EQ(share_in_beam_row("vlp16.yaml", velodyne_cloud), 1.0);
}
