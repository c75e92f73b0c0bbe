#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "adaptive_lego_loam/core/motion_sensors/wheel_odometry.h"
#include "support/motion_samples.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

std::deque<WheelOdometrySample> wheel_samples(const PoseAt& body, double from, double to,
                                              double rate, double scale = 1.0) {
  std::deque<WheelOdometrySample> samples;
  for (int i = 0; from + i / rate <= to + 1e-9; ++i)
    samples.push_back(wheel_sample(body, from + i / rate, Eigen::Isometry3d::Identity(), scale));
  return samples;
}

}  // namespace

TEST(WheelOdometry, ConstantTurnIntegratesToTheArc) {
  const PoseAt body = constant_turn(5.0, 0.4);
  const std::deque<WheelOdometrySample> samples = wheel_samples(body, 0.0, 2.0, 200.0);
  const std::optional<WheelMotion> wheel =
      integrate_wheel(samples, 0.5, 1.5, WheelOdometryParams());
  ASSERT_TRUE(wheel);
  const Eigen::Isometry3d truth = body(0.5).inverse() * body(1.5);
  EXPECT_LT((wheel->motion.translation() - truth.translation()).norm(), 0.02);
  EXPECT_NEAR(Eigen::AngleAxisd(wheel->motion.linear()).angle(), 0.4, 1e-6);
  EXPECT_NEAR(wheel->distance, 5.0, 1e-6);
}

TEST(WheelOdometry, AGapOrNoSampleBeforeTheIntervalIsNoMotion) {
  const PoseAt body = constant_turn(5.0, 0.0);
  std::deque<WheelOdometrySample> samples = wheel_samples(body, 0.0, 2.0, 50.0);
  WheelOdometryParams params;
  EXPECT_FALSE(integrate_wheel(samples, -0.1, 0.5, params));
  samples.erase(samples.begin() + 30, samples.begin() + 60);  // 0.6 s missing
  EXPECT_FALSE(integrate_wheel(samples, 0.2, 1.5, params));
  EXPECT_TRUE(integrate_wheel(samples, 1.3, 1.5, params));
}

TEST(WheelOdometry, PriorConstrainsDistanceAndYawNotRollOrPitch) {
  const PoseAt body = constant_turn(10.0, 0.0);
  const std::optional<WheelMotion> wheel =
      integrate_wheel(wheel_samples(body, 0.0, 1.0, 50.0), 0.0, 0.1, WheelOdometryParams());
  ASSERT_TRUE(wheel);
  // The LiDAR 1.73 m above the base and 0.5 m ahead of it.
  Eigen::Isometry3d lidar_from_base = Eigen::Isometry3d::Identity();
  lidar_from_base.translation() = Eigen::Vector3d(-0.5, 0.0, -1.73);
  const MotionPrior prior = wheel_prior(*wheel, 1.02, 0.005, lidar_from_base);
  EXPECT_NEAR(prior.motion.translation().x(), 1.02, 1e-9);
  Eigen::SelfAdjointEigenSolver<Matrix6d> solver(prior.information);
  EXPECT_NEAR(solver.eigenvalues()(0), 0.0, 1e-6);  // roll and pitch: no information
  EXPECT_NEAR(solver.eigenvalues()(1), 0.0, 1e-6);
  EXPECT_GT(prior.information(3, 3), 1e4);  // forward distance to about a centimetre
}

TEST(WheelScale, LearnsTheScaleFromTheLidarsDistances) {
  WheelScale scale;
  for (int i = 0; i < 200; ++i)
    scale.add(1.0, 1.025, 0.01);
  EXPECT_NEAR(scale.scale(), 1.025, 0.001);
  EXPECT_LT(scale.sigma(), 0.003);
}
