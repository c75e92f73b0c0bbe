// derive_config's measurements (core/projection/sensor_survey.h) on real scans: KITTI's HDL-64E
// from the order of its points (one laser after the other) and a VLP-16 from its ring field, each
// against its shipped config; and clouds that are not a spinning LiDAR's.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "adaptive_lego_loam/core/projection/sensor_survey.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;

namespace {

const std::string kData = TEST_DATA_DIR;

SensorParams config_sensor(const std::string& name) {
  return load_config(std::string(CONFIG_DIR) + "/" + name + ".yaml").sensor;
}

// A point `range` away in the direction (azimuth, elevation), degrees.
ScanPoint point_at(double azimuth_deg, double elevation_deg, double range) {
  const double a = azimuth_deg * M_PI / 180.0, e = elevation_deg * M_PI / 180.0;
  ScanPoint p;
  p.x = static_cast<float>(range * std::cos(e) * std::cos(a));
  p.y = static_cast<float>(range * std::cos(e) * std::sin(a));
  p.z = static_cast<float>(range * std::sin(e));
  return p;
}

}  // namespace

TEST(SensorSurvey, KittisBeamsFromTheOrderOfItsPoints) {
  std::vector<Scan> scans;
  for (const std::string& file : list_scan_files(kData + "/kitti_seq07/velodyne"))
    scans.push_back(read_scan_file(file));
  const SensorSurvey survey = survey_sensor(scans);
  ASSERT_TRUE(survey.not_spinning.empty()) << survey.not_spinning;
  const SensorParams kitti = config_sensor("kitti");
  ASSERT_EQ(survey.beams.size(), 64u);
  EXPECT_NE(survey.rows_from.find("order"), std::string::npos);
  double worst = 0.0, worst_offset = 0.0;
  for (int row = 0; row < 64; ++row) {
    worst = std::max(worst, std::abs(survey.beams[row].elevation_deg - kitti.beam_angles_deg[row]));
    worst_offset =
        std::max(worst_offset, std::abs(survey.beams[row].offset_m - kitti.beam_offsets_m[row]));
  }
  std::printf("[ measured ] KITTI: beams within %.4f deg, origins within %.4f m of kitti.yaml's\n",
              worst, worst_offset);
  EXPECT_LT(worst, 0.1);
  EXPECT_TRUE(survey.offsets_matter);
  const SensorParams derived = surveyed_sensor(survey, "kitti");
  EXPECT_EQ(derived.beam_offsets_m.size(), 64u);
  EXPECT_GE(derived.columns, 2150) << "KITTI's beams hold up to ~2150 points a turn";
  validate(derived, "derived");
}

TEST(SensorSurvey, AVlp16FromItsRingField) {
  const SensorSurvey survey = survey_sensor({read_scan_file(kData + "/vlp16/vlp16_indoor.pcd")});
  ASSERT_TRUE(survey.not_spinning.empty()) << survey.not_spinning;
  EXPECT_EQ(survey.rows_from, "the ring field");
  const SensorParams vlp16 = config_sensor("vlp16");
  // Ring 0 (-15 deg) sent no point in this indoor frame: rings 1-15 are evenly spaced, and its
  // beam continues their spacing.
  ASSERT_EQ(survey.beams.size(), 16u);
  for (int ring = 0; ring < 16; ++ring)
    EXPECT_NEAR(survey.beams[ring].elevation_deg, vlp16.beam_angles_deg[ring], 0.1) << ring;
  EXPECT_EQ(survey.beams.front().points, 0);
  EXPECT_FALSE(survey.offsets_matter);
  EXPECT_TRUE(survey.ring_to_row.empty()) << "rings count the rows from the bottom";
}

TEST(SensorSurvey, ASolidStateFieldOfViewIsNoSpinningLidar) {
  Scan scan;
  for (int i = 0; i < 20000; ++i)
    scan.points.push_back(point_at(-35.0 + 70.0 * (i % 200) / 200, -20.0 + 0.4 * (i / 200), 20.0));
  const SensorSurvey survey = survey_sensor({scan});
  EXPECT_NE(survey.not_spinning.find("cover 70 deg of azimuth"), std::string::npos)
      << survey.not_spinning;
}

TEST(SensorSurvey, ARosetteOfContinuousElevationsIsNoSpinningLidar) {
  // A Mid-360-like pattern: every azimuth, elevations anywhere from -7 to 52 deg.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> azimuth(-180.0, 180.0), elevation(-7.0, 52.0);
  Scan scan;
  for (int i = 0; i < 20000; ++i)
    scan.points.push_back(point_at(azimuth(rng), elevation(rng), 15.0));
  const SensorSurvey survey = survey_sensor({scan});
  EXPECT_NE(survey.not_spinning.find("no discrete beams"), std::string::npos)
      << survey.not_spinning;
}

TEST(SensorSurvey, TwoSensorsMergedIntoOneCloudAreNoOneSpinningLidar) {
  // Two VLP-16s 1.5 m apart in height, their rings both 0-15, in one cloud.
  const SensorParams sensor = test::even_sensor(16, 900, -15.0, 15.0);
  test::Scene scene;
  scene.has_ground = true;
  scene.ground_z = -1.8;
  scene.boxes = {{{10.0, -11.0, -5.0}, {11.0, 11.0, 5.0}},
                 {{-11.0, -11.0, -5.0}, {-10.0, 11.0, 5.0}},
                 {{-11.0, 10.0, -5.0}, {11.0, 11.0, 5.0}},
                 {{-11.0, -11.0, -5.0}, {11.0, -10.0, 5.0}}};
  Scan merged = test::render(sensor, scene);
  const Eigen::Isometry3d raised(Eigen::Translation3d(0.0, 0.0, 1.5));
  for (ScanPoint p : test::render(sensor, scene, raised).points) {
    p.z += 1.5f;  // into the lower sensor's frame
    merged.points.push_back(p);
  }
  EXPECT_TRUE(survey_sensor({test::render(sensor, scene)}).not_spinning.empty());
  const SensorSurvey survey = survey_sensor({merged});
  EXPECT_NE(survey.not_spinning.find("lie on no one cone"), std::string::npos)
      << survey.not_spinning;
}
