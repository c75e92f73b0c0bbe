// Whether a config fits the clouds: the right configs pass real KITTI and VLP-16 scans, a wrong
// beam table, too few columns or too many rows are named, once; and which config reads the scans
// of a sensor.

#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/projection/config_fit.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;

namespace {

const std::string kData = TEST_DATA_DIR;

SensorParams config_sensor(const std::string& name) {
  return load_config(std::string(CONFIG_DIR) + "/" + name + ".yaml").sensor;
}

Scan kitti_frame() {
  return read_scan_file(kData + "/kitti_seq07/velodyne/0000000000.bin");
}
Scan vlp16_frame() {
  return read_scan_file(kData + "/vlp16/vlp16_indoor.pcd");
}

std::vector<std::string> problems(const SensorParams& sensor, const Scan& scan) {
  RangeImage image;
  RangeProjector(sensor).project(scan, image);
  return check_config_fit(sensor, image, rows_from_ring(sensor, scan.has_ring)).problems();
}

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const std::string& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(ConfigFit, TheShippedConfigsFitRealScans) {
  EXPECT_TRUE(problems(config_sensor("kitti"), kitti_frame()).empty());
  EXPECT_TRUE(problems(config_sensor("vlp16"), vlp16_frame()).empty());
}

// config/hdl64e.yaml's beams are KITTI's, but without the origins 0.12-0.2 m above the sensor's:
// KITTI's ring-less scans land in the wrong rows, which is what LeGO-LOAM users see as drift.
TEST(ConfigFit, ABeamTableWithoutTheBeamsOriginsIsNamed) {
  const std::vector<std::string> found = problems(config_sensor("hdl64e"), kitti_frame());
  EXPECT_TRUE(mentions(found, "from their row's beam (rows from the elevation)")) << found.size();
}

TEST(ConfigFit, AnotherSensorsConfigIsNamedFromTheRingFieldToo) {
  // The VLP-16's 16 rings read as the HDL-32E's lowest 16 rows.
  const std::vector<std::string> found = problems(config_sensor("hdl32"), vlp16_frame());
  EXPECT_TRUE(mentions(found, "(rows from the ring field)"));
  // KITTI's 64 beams binned into a VLP-16's 16 rows.
  const std::vector<std::string> vlp16 = problems(config_sensor("vlp16"), kitti_frame());
  EXPECT_TRUE(mentions(vlp16, "found no free column"));
  EXPECT_TRUE(mentions(vlp16, "fall outside the rows"));
}

TEST(ConfigFit, EmptyRowsBetweenFullOnesAreNamed) {
  // 16 beams read with a table of 31 rows from the same limits: every other row stays empty.
  SensorParams sensor16 = test::even_sensor(16, 900, -15.0, 15.0);
  sensor16.row_source = RowSource::kElevation;
  test::Scene scene;  // four walls round the sensor, every beam hits one
  scene.boxes = {{{10.0, -11.0, -5.0}, {11.0, 11.0, 5.0}},
                 {{-11.0, -11.0, -5.0}, {-10.0, 11.0, 5.0}},
                 {{-11.0, 10.0, -5.0}, {11.0, 11.0, 5.0}},
                 {{-11.0, -11.0, -5.0}, {11.0, -10.0, 5.0}}};
  const Scan scan = test::render(sensor16, scene);
  SensorParams sensor31 = test::even_sensor(31, 900, -15.0, 15.0);
  sensor31.row_source = RowSource::kElevation;
  EXPECT_TRUE(problems(sensor16, scan).empty());
  EXPECT_TRUE(mentions(problems(sensor31, scan), "15 of the 31 rows got no point"));
}

TEST(ConfigFit, TheWarningComesOnceNamingTheConfigInputAndDeriveConfig) {
  const SensorParams sensor = config_sensor("hdl64e");
  RangeImage image;
  RangeProjector(sensor).project(kitti_frame(), image);
  ConfigFitWarning warning("config/hdl64e.yaml", "/velodyne_points");
  const auto first = warning.check(sensor, image, false);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->rfind("config/hdl64e.yaml does not fit the clouds of /velodyne_points: ", 0), 0u)
      << *first;
  EXPECT_NE(first->find("derive_config --input"), std::string::npos);
  EXPECT_FALSE(warning.check(sensor, image, false).has_value());
  EXPECT_FALSE(warning.seen().empty());
}

TEST(ConfigFit, WhichConfigReadsASensorsScans) {
  const SensorParams kitti = config_sensor("kitti");
  // KITTI's HDL-64E fires 2083 times a turn: kitti.yaml reads its ring-less scans, hdl64e.yaml
  // only clouds with a ring field.
  EXPECT_TRUE(config_reads(kitti, kitti, 2083, false));
  EXPECT_FALSE(config_reads(config_sensor("hdl64e"), kitti, 2083, false));
  EXPECT_TRUE(config_reads(config_sensor("hdl64e"), kitti, 2083, true));
  const SensorParams os1 = config_sensor("os1_64");
  EXPECT_TRUE(config_reads(os1, os1, 1024, true));
  EXPECT_FALSE(config_reads(os1, os1, 2048, true)) << "2048x10 needs 2048 columns";
  SensorParams bottom_up = os1;
  bottom_up.ring_to_row.clear();
  EXPECT_FALSE(config_reads(bottom_up, os1, 1024, true)) << "ouster-ros numbers rings top-down";
  EXPECT_TRUE(config_reads(bottom_up, os1, 1024, false)) << "no ring: the beams alone";
  SensorParams at_20_hz = os1;
  at_20_hz.scan_period = 0.05;
  EXPECT_FALSE(config_reads(at_20_hz, os1, 1024, true));
}
