// The simulated wheel odometry reports the base frame's forward speed and yaw rate with the
// seed's scale error, sees the lever arm in a turn, rolls with the chassis on a rough road, shows
// its slips, and integrates as a driver would.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/sim/wheel_odometry_model.h"
#include "sim/motion_drives.h"
#include "support/motion_samples.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

namespace {

WheelOdometryOptions error_free() {
  WheelOdometryOptions options;
  options.scale_error = options.noise = options.slips = false;
  return options;
}

PoseFunction straight(double speed) {
  return [=](double t) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation().x() = speed * t;
    return pose;
  };
}

}  // namespace

TEST(WheelOdometryModel, ReportsTheSpeedWithTheSeedsScaleError) {
  WheelOdometryOptions options = error_free();
  options.scale_error = true;
  const WheelOdometryModel model(options, 4);
  const double scale = model.errors().scale_error;
  EXPECT_GE(std::abs(scale), 0.01);
  EXPECT_LE(std::abs(scale), 0.03);
  const WheelOdometryRun run = model.simulate(*smooth_drive(straight(10.0), 4.0), 0.0, 4.0);
  ASSERT_EQ(run.samples.size(), 201u);  // 50 Hz
  for (const WheelOdometrySample& s : run.samples) {
    EXPECT_NEAR(s.linear_velocity.x(), 10.0 * (1.0 + scale), 1e-9);
    EXPECT_NEAR(s.angular_velocity.z(), 0.0, 1e-9);
    EXPECT_EQ(s.linear_velocity.y(), 0.0);
    EXPECT_DOUBLE_EQ(s.linear_x_variance, 0.05 * 0.05);  // as configured, not the truth
  }
  // Seeds draw scale errors of either sign.
  bool positive = false, negative = false;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const double s = WheelOdometryModel(options, seed).errors().scale_error;
    positive |= s > 0.0;
    negative |= s < 0.0;
  }
  EXPECT_TRUE(positive && negative);
}

// In a turn the rear axle, under the LiDAR, rolls at the LiDAR's speed and turns at its yaw rate;
// nothing is reported sideways.
TEST(WheelOdometryModel, TheBaseFramesMotionInATurn) {
  const double speed = 8.0, yaw_rate = 0.4;
  const WheelOdometryRun run =
      WheelOdometryModel(error_free(), 1)
          .simulate(*smooth_drive(turning(speed, yaw_rate), 5.0), 1.0, 4.0);
  for (const WheelOdometrySample& s : run.samples) {
    EXPECT_NEAR(s.linear_velocity.x(), speed, 2e-3);
    EXPECT_NEAR(s.angular_velocity.z(), yaw_rate, 1e-5);
    EXPECT_EQ(s.linear_velocity.y(), 0.0);
  }
}

// The core's tests difference the base frame's poses (support/motion_samples.h): the error-free
// odometry reports that forward speed and yaw rate with the same mount convention.
TEST(WheelOdometryModel, ReportsWhatTheCoresTestsExpectOfAWheelOdometry) {
  const auto drive = smooth_drive(winding(), 8.0);
  const WheelOdometryOptions options = error_free();
  const WheelOdometryRun run = WheelOdometryModel(options, 1).simulate(*drive, 1.0, 7.0);
  const auto pose = [&](double t) { return drive->sensor_pose(t); };
  for (std::size_t i = 0; i < run.samples.size(); i += 17) {
    const WheelOdometrySample& sample = run.samples[i];
    const WheelOdometrySample expected =
        adaptive_lego_loam::test::wheel_sample(pose, sample.stamp, options.lidar_from_base());
    EXPECT_NEAR(sample.linear_velocity.x(), expected.linear_velocity.x(), 1e-4) << sample.stamp;
    EXPECT_NEAR(sample.angular_velocity.z(), expected.angular_velocity.z(), 1e-5) << sample.stamp;
  }
}

// On a rough road the body, and the LiDAR on it, shakes on its suspension while the wheels roll
// on the road: the odometry reads the chassis' motion at the base, not that of a point swung by
// the body's roll and pitch 1.7 m below the LiDAR; with its noise, within that noise.
TEST(WheelOdometryModel, OnARoughRoadTheWheelsRollWithTheChassis) {
  const auto drive = smooth_drive(winding(), 8.0, Shake(ShakeParams(), 5));
  const auto chassis = [&](double t) { return drive->unshaken_pose(t); };
  const auto body = [&](double t) { return drive->sensor_pose(t); };
  WheelOdometryOptions options = error_free();
  const Eigen::Isometry3d lidar_from_base = options.lidar_from_base();
  const WheelOdometryRun run = WheelOdometryModel(options, 1).simulate(*drive, 1.0, 7.0);
  double body_error = 0.0;
  for (const WheelOdometrySample& sample : run.samples) {
    const WheelOdometrySample expected =
        adaptive_lego_loam::test::wheel_sample(chassis, sample.stamp, lidar_from_base);
    EXPECT_NEAR(sample.linear_velocity.x(), expected.linear_velocity.x(), 1e-4) << sample.stamp;
    EXPECT_NEAR(sample.angular_velocity.z(), expected.angular_velocity.z(), 1e-5) << sample.stamp;
    const WheelOdometrySample on_body =
        adaptive_lego_loam::test::wheel_sample(body, sample.stamp, lidar_from_base);
    body_error =
        std::max(body_error, std::abs(sample.linear_velocity.x() - on_body.linear_velocity.x()));
  }
  EXPECT_GT(body_error, 0.1);  // m/s: what a base on the shaking body would read

  options.noise = true;
  const WheelOdometryRun noisy = WheelOdometryModel(options, 1).simulate(*drive, 1.0, 7.0);
  double sum = 0.0, square_sum = 0.0;
  for (std::size_t i = 0; i < noisy.samples.size(); ++i) {
    const double error = noisy.samples[i].linear_velocity.x() - run.samples[i].linear_velocity.x();
    sum += error;
    square_sum += error * error;
  }
  const double count = static_cast<double>(noisy.samples.size());
  const double speed_noise = options.wheel_speed_noise / std::sqrt(2.0);  // of (l + r) / 2
  EXPECT_LT(std::abs(sum / count), 0.25 * speed_noise);
  EXPECT_NEAR(std::sqrt(square_sum / count), speed_noise, 0.2 * speed_noise);
}

// A wheel spinning on a wet patch: the speed over the true one by tens of percent, and a yaw rate
// on a straight road.
TEST(WheelOdometryModel, SlipsShowInSpeedAndYawRate) {
  WheelOdometryOptions options = error_free();
  options.slips = true;
  options.min_slips_per_km = options.max_slips_per_km = 20.0;
  const WheelOdometryModel model(options, 3);
  const WheelOdometryRun run = model.simulate(*smooth_drive(straight(10.0), 30.0), 0.0, 30.0);
  ASSERT_GE(run.slips.size(), 2u);
  for (const SlipEvent& slip : run.slips) {
    const double peak = slip.start_s + 0.5 * slip.duration_s;
    const WheelOdometrySample* at_peak = nullptr;
    for (const WheelOdometrySample& s : run.samples)
      if (!at_peak || std::abs(s.stamp - peak) < std::abs(at_peak->stamp - peak)) at_peak = &s;
    EXPECT_GT(at_peak->linear_velocity.x(), 10.0 * 1.09) << slip.start_s;
    EXPECT_GT(std::abs(at_peak->angular_velocity.z()), 1.0) << slip.start_s;
    EXPECT_EQ(at_peak->angular_velocity.z() > 0.0, !slip.left_wheel);  // the faster side
  }
  // Between slips the speed is the true one.
  int clean = 0;
  for (const WheelOdometrySample& s : run.samples) {
    bool slipping = false;
    for (const SlipEvent& slip : run.slips)
      slipping |= s.stamp >= slip.start_s && s.stamp <= slip.start_s + slip.duration_s;
    if (!slipping) {
      EXPECT_NEAR(s.linear_velocity.x(), 10.0, 1e-9) << s.stamp;
      ++clean;
    }
  }
  EXPECT_GT(clean, 500);
}

TEST(WheelOdometryModel, TheSameSeedGivesTheSameSamples) {
  const auto drive = smooth_drive(winding(), 20.0);
  WheelOdometryOptions options;
  options.min_slips_per_km = options.max_slips_per_km = 10.0;
  const WheelOdometryRun a = WheelOdometryModel(options, 8).simulate(*drive, 0.0, 20.0);
  const WheelOdometryRun b = WheelOdometryModel(options, 8).simulate(*drive, 0.0, 20.0);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].linear_velocity, b.samples[i].linear_velocity);
    EXPECT_EQ(a.samples[i].angular_velocity, b.samples[i].angular_velocity);
  }
  ASSERT_EQ(a.slips.size(), b.slips.size());
  const WheelOdometryRun c = WheelOdometryModel(options, 9).simulate(*drive, 0.0, 20.0);
  EXPECT_NE(a.samples[100].linear_velocity, c.samples[100].linear_velocity);
}

// A constant twist integrates to a circle, as a driver's pose does.
TEST(WheelOdometryModel, IntegratesTheTwistAsADriver) {
  std::vector<WheelOdometrySample> samples;
  for (int k = 0; k <= 500; ++k) {
    WheelOdometrySample s;
    s.stamp = 0.02 * k;
    s.linear_velocity.x() = 5.0;
    s.angular_velocity.z() = 0.5;
    samples.push_back(s);
  }
  samples[10].linear_velocity.x() = std::nan("");  // skipped
  const std::vector<Eigen::Isometry3d> poses = integrate_odometry(samples);
  ASSERT_EQ(poses.size(), samples.size());
  const double heading = 0.5 * 10.0, radius = 10.0;
  EXPECT_NEAR(poses.back().translation().x(), radius * std::sin(heading), 1e-3);
  EXPECT_NEAR(poses.back().translation().y(), radius * (1.0 - std::cos(heading)), 1e-3);
  EXPECT_TRUE(poses.front().isApprox(Eigen::Isometry3d::Identity()));
}
