// sensors.yaml holds config sections load_config takes, with the simulated sensors' true
// extrinsics; scenario.yaml records the errors drawn.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/sim/run_description.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

RunDescription with_motion_sensors() {
  RunDescription run;
  const ImuModel imu(ImuOptions(), 3);
  run.imu = ImuDescription{imu.options(), imu.errors()};
  const WheelOdometryModel wheel(WheelOdometryOptions(), 3);
  run.wheel_odometry = WheelOdometryDescription{wheel.options(), wheel.errors(), {}};
  run.wheel_odometry->slips.push_back({12.5, 0.8, 0.4, true});
  return run;
}

}  // namespace

TEST(RunDescription, SensorsYamlIsAConfigFragment) {
  // Given after a sensor's config, its sections replace the config's.
  const RunDescription run = with_motion_sensors();
  const std::string path = adaptive_lego_loam::test::temp_path("sensors.yaml");
  std::ofstream(path) << sensors_yaml(run);
  const Config config = load_config({std::string(CONFIG_DIR) + "/kitti.yaml", path});
  EXPECT_EQ(config.imu.extrinsic_rpy_deg, std::vector<double>({180.0, 2.5, 90.0}));
  EXPECT_EQ(config.imu.extrinsic_xyz_m, std::vector<double>({-0.12, 0.08, -0.18}));
  EXPECT_NEAR(config.imu.gyro_noise_density / adis16448().gyro_noise_density, 1.0, 1e-9);
  EXPECT_NEAR(config.imu.gyro_bias_sigma / adis16448().gyro_turn_on_bias, 1.0, 1e-9);
  EXPECT_EQ(config.wheel_odometry.extrinsic_xyz_m, std::vector<double>({0.0, 0.0, -1.73}));
  EXPECT_DOUBLE_EQ(config.wheel_odometry.speed_sigma, 0.05);
}

TEST(RunDescription, ScenarioYamlRecordsTheErrorsDrawn) {
  const RunDescription run = with_motion_sensors();
  const std::string yaml = run_yaml(run);
  for (const char* key :
       {"datasheet: Analog Devices ADIS16448", "gyro_turn_on_bias:", "accel_turn_on_bias:",
        "scale_error:", "track_width_error:", "start_s: 12.5", "mount_rpy_deg: [180, 2.5, 90]"})
    EXPECT_NE(yaml.find(key), std::string::npos) << key << "\n" << yaml;
  EXPECT_EQ(run_yaml(RunDescription()).find("imu"), std::string::npos);
}
