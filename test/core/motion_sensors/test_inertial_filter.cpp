#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/motion_sensors/inertial_filter.h"
#include "support/motion_samples.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

constexpr double kRate = 200.0;  // Hz

// Integrates samples over [from, to] with the trapezoid of consecutive samples, as the stage does.
void run(InertialFilter& filter, const std::vector<ImuSample>& samples) {
  for (std::size_t i = 1; i < samples.size(); ++i) {
    filter.propagate(samples[i].stamp,
                     0.5 * (samples[i - 1].angular_velocity + samples[i].angular_velocity),
                     0.5 * (samples[i - 1].linear_acceleration + samples[i].linear_acceleration));
  }
}

ImuParams quiet_imu() {
  ImuParams params;
  params.gyro_noise_density = 1e-4;
  params.accel_noise_density = 1e-3;
  return params;
}

Matrix6d exact_information() {
  Matrix6d information = Matrix6d::Identity();
  information.topLeftCorner<3, 3>() *= 1e8;      // 0.1 mrad
  information.bottomRightCorner<3, 3>() *= 1e6;  // 1 mm
  return information;
}

}  // namespace

TEST(InertialFilter, ConstantTurnIntegratesToTheClosedFormArc) {
  const PoseAt body = constant_turn(10.0, 0.3);
  const std::vector<ImuSample> samples =
      imu_samples(body, 0.0, 1.0, kRate, Eigen::Isometry3d::Identity());
  InertialFilter filter(quiet_imu());
  // Levelled by gravity alone: the reading also holds the turn's centripetal acceleration.
  filter.initialize(0.0, Eigen::Vector3d(0.0, 0.0, 9.81), Eigen::Vector3d(10.0, 0.0, 0.0), 0.1);
  run(filter, samples);
  const Eigen::Isometry3d truth = body(0.0).inverse() * body(1.0);
  const Eigen::Isometry3d motion = filter.motion_since_mark();
  EXPECT_LT((motion.translation() - truth.translation()).norm(), 2e-3);
  EXPECT_LT(rotation_log(motion.linear().transpose() * truth.linear()).norm(), 1e-5);
  // The uncertainty grows with the time integrated, and the velocity's dominates the position's.
  EXPECT_GT(filter.motion_covariance()(3, 3), 0.005);  // 0.1 m/s over 1 s, squared: 0.01
}

TEST(InertialFilter, StandingStillStaysPut) {
  const PoseAt body = constant_turn(0.0, 0.0);
  const std::vector<ImuSample> samples =
      imu_samples(body, 0.0, 10.0, kRate, Eigen::Isometry3d::Identity());
  InertialFilter filter(quiet_imu());
  filter.initialize(0.0, samples.front().linear_acceleration, Eigen::Vector3d::Zero(), 0.01);
  run(filter, samples);
  EXPECT_LT(filter.motion_since_mark().translation().norm(), 1e-6);
  EXPECT_NEAR(filter.up_in_imu().z(), 1.0, 1e-9);
}

TEST(InertialFilter, StartsLevelledByTheSpecificForce) {
  // Upside down and tilted: up, in the IMU's frame, is where the accelerometer reads +g.
  const Eigen::Vector3d up = Eigen::Vector3d(0.1, -0.05, -1.0).normalized();
  InertialFilter filter(quiet_imu());
  filter.initialize(0.0, 9.81 * up, Eigen::Vector3d::Zero(), 0.1);
  EXPECT_LT((filter.up_in_imu() - up).norm(), 1e-12);
  // ... and stays so at rest.
  filter.propagate(1.0, Eigen::Vector3d::Zero(), 9.81 * up);
  EXPECT_LT(filter.state().velocity.norm(), 1e-9);
}

TEST(InertialFilter, LidarMotionsTeachItTheGyroBias) {
  const PoseAt body = constant_turn(8.0, 0.2);
  std::vector<ImuSample> samples =
      imu_samples(body, 0.0, 30.0, kRate, Eigen::Isometry3d::Identity());
  const Eigen::Vector3d bias(0.004, -0.003, 0.01);  // rad/s
  for (ImuSample& s : samples)
    s.angular_velocity += bias;
  InertialFilter filter(quiet_imu());
  filter.initialize(0.0, Eigen::Vector3d(0.0, 0.0, 9.81), Eigen::Vector3d(8.0, 0.0, 0.0), 0.1);
  const int per_scan = static_cast<int>(kRate / 10);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    filter.propagate(samples[i].stamp,
                     0.5 * (samples[i - 1].angular_velocity + samples[i].angular_velocity),
                     0.5 * (samples[i - 1].linear_acceleration + samples[i].linear_acceleration));
    if (i % per_scan != 0) continue;
    const double now = samples[i].stamp, then = now - 0.1;
    ASSERT_TRUE(filter.update_motion(body(then).inverse() * body(now), exact_information()));
    filter.mark_scan();
  }
  EXPECT_LT((filter.state().gyro_bias - bias).norm(), 3e-4) << filter.state().gyro_bias.transpose();
}

TEST(InertialFilter, TurningSeparatesTheAccelerometerBiasFromTheTilt) {
  // Driving circles, the accelerometer's bias turns with the body and gravity does not.
  const PoseAt body = constant_turn(5.0, 0.5);
  std::vector<ImuSample> samples =
      imu_samples(body, 0.0, 40.0, kRate, Eigen::Isometry3d::Identity());
  const Eigen::Vector3d bias(0.15, -0.1, 0.05);  // m/s^2
  for (ImuSample& s : samples)
    s.linear_acceleration += bias;
  InertialFilter filter(quiet_imu());
  // Levelled by the biased reading without the turn's 2.5 m/s^2: tilted by about 1 deg at first.
  filter.initialize(0.0, samples.front().linear_acceleration - Eigen::Vector3d(0.0, 2.5, 0.0),
                    Eigen::Vector3d(5.0, 0.0, 0.0), 0.1);
  const int per_scan = static_cast<int>(kRate / 10);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    filter.propagate(samples[i].stamp,
                     0.5 * (samples[i - 1].angular_velocity + samples[i].angular_velocity),
                     0.5 * (samples[i - 1].linear_acceleration + samples[i].linear_acceleration));
    if (i % per_scan != 0) continue;
    const double now = samples[i].stamp, then = now - 0.1;
    filter.update_motion(body(then).inverse() * body(now), exact_information());
    filter.mark_scan();
  }
  EXPECT_LT((filter.state().accel_bias - bias).norm(), 0.02)
      << filter.state().accel_bias.transpose();
  // Level again: the body's up in its own frame is z.
  EXPECT_LT(std::acos(std::min(1.0, filter.up_in_imu().z())), 0.002);
}

TEST(InertialFilter, AGateRefusesAWildMeasurementAndSingularInformationLeavesDirectionsAlone) {
  const PoseAt body = constant_turn(10.0, 0.0);
  const std::vector<ImuSample> samples =
      imu_samples(body, 0.0, 0.1, kRate, Eigen::Isometry3d::Identity());
  InertialFilter filter(quiet_imu());
  filter.initialize(0.0, samples.front().linear_acceleration, Eigen::Vector3d(10.0, 0.0, 0.0),
                    0.01);
  run(filter, samples);
  Eigen::Isometry3d wild = body(0.0).inverse() * body(0.1);
  wild.translation().x() += 5.0;
  EXPECT_FALSE(filter.update_motion(wild, exact_information(), 5.0));
  // Information across the road only: the forward motion stays the filter's.
  Matrix6d across = Matrix6d::Zero();
  across(4, 4) = 1e6;
  const double forward = filter.motion_since_mark().translation().x();
  EXPECT_TRUE(filter.update_motion(wild, across));
  EXPECT_NEAR(filter.motion_since_mark().translation().x(), forward, 1e-6);
}
