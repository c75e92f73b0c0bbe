// feature_association's motion sensors on /diagnostics.

#include <gtest/gtest.h>

#include <limits>
#include <map>

#include "adaptive_lego_loam/ros/motion_sensor_diagnostics.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;

namespace {

std::map<std::string, std::string> values_of(const HealthStatus& status) {
  return {status.values.begin(), status.values.end()};
}

ImuSample still_imu(double t) {
  ImuSample sample;
  sample.stamp = t;
  sample.linear_acceleration.z() = 9.81;
  return sample;
}

}  // namespace

TEST(MotionSensorDiagnostics, CountsEachFaultAndWarnsOnNewOnesOnly) {
  MotionSensorRelay relay(Config(), {true, false}, 0.2);
  MotionSensorDiagnostics diagnostics("/imu/data", "");
  diagnostics.set_imu_extrinsic_source("TF velodyne -> imu");
  for (int i = 0; i <= 20; ++i) {
    ImuSample sample = still_imu(i * 0.005);
    if (i == 5) sample.angular_velocity.x() = std::numeric_limits<double>::quiet_NaN();
    if (i == 9) sample.stamp = 8 * 0.005;  // repeated
    relay.add_imu(sample, 0.0);
  }
  relay.predict(0.1, 0.1, ScanRelease::kTimeout, 0.0);
  HealthStatus status;
  diagnostics.add_to(relay, status);
  auto values = values_of(status);
  EXPECT_EQ(values["IMU topic"], "/imu/data");
  EXPECT_EQ(values["IMU samples accepted"], "19");
  EXPECT_EQ(values["IMU dropped: not finite"], "1");
  EXPECT_EQ(values["IMU dropped: repeated stamp"], "1");
  EXPECT_EQ(values["IMU dropped: out of order"], "0");
  EXPECT_EQ(values["IMU extrinsic"], "TF velodyne -> imu");
  EXPECT_EQ(values["scans processed on the sensor timeout (total)"], "1");
  EXPECT_EQ(values.count("wheel odometry samples accepted"), 0u) << "not configured";
  EXPECT_FALSE(values["gyro bias (rad/s)"].empty());
  EXPECT_EQ(status.level, HealthLevel::kWarn);
  EXPECT_NE(status.message.find("IMU samples dropped"), std::string::npos) << status.message;

  HealthStatus next;  // nothing new since
  diagnostics.add_to(relay, next);
  EXPECT_EQ(next.level, HealthLevel::kOk) << next.message;
}

TEST(MotionSensorDiagnostics, WarnsWhenAConfiguredInputSentNothing) {
  MotionSensorRelay relay(Config(), {true, true}, 0.2);
  MotionSensorDiagnostics diagnostics("/imu/data", "/odom");
  HealthStatus before_first_scan;
  diagnostics.add_to(relay, before_first_scan);
  EXPECT_EQ(before_first_scan.level, HealthLevel::kOk);
  relay.add_imu(still_imu(0.0), 0.0);
  relay.predict(0.0, 0.1, ScanRelease::kReady, 0.0);
  HealthStatus status;
  diagnostics.add_to(relay, status);
  EXPECT_EQ(status.level, HealthLevel::kWarn);
  EXPECT_NE(status.message.find("no wheel odometry sample on /odom"), std::string::npos)
      << status.message;
  EXPECT_EQ(status.message.find("no IMU sample"), std::string::npos) << status.message;
  EXPECT_EQ(values_of(status)["wheel odometry in use"], "no");
}

TEST(MotionSensorDiagnostics, WarnsWhileAnInputThatWasInUseIsOut) {
  MotionSensorRelay relay(Config(), {false, true}, 0.2);
  MotionSensorDiagnostics diagnostics("", "/odom");
  const auto wheel_at = [](double t) {
    WheelOdometrySample sample;
    sample.stamp = t;
    sample.linear_velocity.x() = 5.0;
    return sample;
  };
  for (int i = 0; i <= 10; ++i)
    relay.add_wheel(wheel_at(i * 0.02), 0.0);  // up to 0.2 s, then nothing
  for (double stamp : {0.1, 0.2}) {
    relay.predict(stamp, 0.1, ScanRelease::kReady, 0.0);
    relay.add_feedback(stamp, std::nullopt, Matrix6d::Zero());
  }
  HealthStatus in_use;
  diagnostics.add_to(relay, in_use);
  EXPECT_EQ(values_of(in_use)["wheel odometry in use"], "yes");
  EXPECT_EQ(in_use.level, HealthLevel::kOk) << in_use.message;

  relay.predict(0.6, 0.1, ScanRelease::kTimeout, 0.0);  // the wheel stopped
  HealthStatus out;
  diagnostics.add_to(relay, out);
  EXPECT_EQ(values_of(out)["wheel odometry scans LiDAR-only"], "1");
  EXPECT_EQ(out.level, HealthLevel::kWarn);
  EXPECT_NE(out.message.find("wheel odometry fell back to LiDAR-only"), std::string::npos)
      << out.message;
}
