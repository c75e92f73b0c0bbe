// The simulated IMU reads what an IMU mounted where it is would: the centripetal acceleration and
// yaw rate of a turn in its own axes, gravity at rest, readings that integrate back to the
// trajectory; its noise has the datasheet's density and its errors come from the seed.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/io/motion_sensor_files.h"
#include "adaptive_lego_loam/sim/imu_model.h"
#include "sim/motion_drives.h"
#include "support/motion_samples.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

namespace {

ImuOptions error_free() {
  ImuOptions options;
  options.white_noise = options.bias_random_walk = options.turn_on_bias = false;
  return options;
}

std::string file_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

}  // namespace

// 12 m/s round a 40 m radius: 3.6 m/s^2 towards the centre, 0.3 rad/s; the IMU sits 0.23 m from
// the LiDAR, upside down and turned, so it reads those plus its own centripetal term, in its axes.
TEST(ImuModel, AConstantTurnReadsTheCentripetalAccelerationAndYawRate) {
  const double speed = 12.0, yaw_rate = 0.3;
  const auto drive = smooth_drive(turning(speed, yaw_rate), 6.0);
  const ImuOptions options = error_free();
  const ImuModel imu(options, 1);
  const Eigen::Isometry3d mount = options.lidar_from_imu();
  const Eigen::Vector3d rate(0.0, 0.0, yaw_rate);
  // In the LiDAR's axes: towards the centre (left), and at the IMU's offset from the LiDAR.
  const Eigen::Vector3d lidar_acceleration(0.0, speed * yaw_rate, 0.0);
  const Eigen::Vector3d imu_acceleration =
      lidar_acceleration + rate.cross(rate.cross(mount.translation()));
  const Eigen::Vector3d expected_force =
      mount.linear().transpose() * (imu_acceleration + Eigen::Vector3d(0.0, 0.0, 9.81));
  const Eigen::Vector3d expected_rate = mount.linear().transpose() * rate;
  for (const ImuSample& sample : imu.simulate(*drive, 1.0, 5.0)) {
    EXPECT_LT((sample.linear_acceleration - expected_force).norm(), 5e-3) << sample.stamp;
    EXPECT_LT((sample.angular_velocity - expected_rate).norm(), 1e-6) << sample.stamp;
  }
  // Upside down and turned 90 deg: the centripetal pull shows on the IMU's x axis.
  EXPECT_GT(std::abs(expected_force.x()), 3.0);
}

TEST(ImuModel, StandingStillReadsGravityAlongItsUpAxis) {
  const auto still = standing(2.0);
  const ImuOptions options = error_free();
  const Eigen::Vector3d up = options.lidar_from_imu().linear().transpose().col(2);
  for (const ImuSample& sample : ImuModel(options, 1).simulate(*still, 0.0, 2.0)) {
    EXPECT_LT((sample.linear_acceleration - 9.81 * up).norm(), 1e-9);
    EXPECT_LT(sample.angular_velocity.norm(), 1e-12);
  }
  EXPECT_LT(up.z(), -0.99);  // mounted upside down: its z axis points down
}

// The core's tests build an IMU's samples by differencing poses (support/motion_samples.h): the
// simulated IMU reads the same with the same mount convention (the IMU's pose in the LiDAR
// frame) and sign of gravity.
TEST(ImuModel, ReadsWhatTheCoresTestsExpectOfAnImu) {
  const auto drive = smooth_drive(winding(), 8.0);
  const ImuOptions options = error_free();
  const ImuModel imu(options, 1);
  const auto pose = [&](double t) { return drive->sensor_pose(t); };
  for (double t = 1.0; t < 7.0; t += 0.377) {
    const ImuSample expected =
        adaptive_lego_loam::test::imu_sample(pose, t, options.lidar_from_imu(), options.gravity);
    const ImuSample sample = imu.exact(drive->motion(t), t);
    EXPECT_LT((sample.angular_velocity - expected.angular_velocity).norm(), 1e-5) << t;
    EXPECT_LT((sample.linear_acceleration - expected.linear_acceleration).norm(), 1e-3) << t;
  }
}

// Strapdown integration (trapezoidal) of the error-free samples from the true initial state
// stays on the IMU's true trajectory over 10 s of a winding, hilly drive.
TEST(ImuModel, ErrorFreeSamplesIntegrateToTheTrajectory) {
  const auto drive = smooth_drive(winding(), 12.0);
  const ImuOptions options = error_free();
  const Eigen::Isometry3d mount = options.lidar_from_imu();
  const std::vector<ImuSample> samples = ImuModel(options, 1).simulate(*drive, 1.0, 11.0);
  const Kinematics start = mounted(drive->motion(1.0), mount);
  Eigen::Matrix3d rotation = start.pose.linear();
  Eigen::Vector3d position = start.pose.translation(), velocity = start.velocity;
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    const double dt = samples[k + 1].stamp - samples[k].stamp;
    const Eigen::Matrix3d next_rotation =
        rotation *
        rotation_exp(0.5 * (samples[k].angular_velocity + samples[k + 1].angular_velocity) * dt);
    const Eigen::Vector3d a0 = rotation * samples[k].linear_acceleration + gravity;
    const Eigen::Vector3d a1 = next_rotation * samples[k + 1].linear_acceleration + gravity;
    position += velocity * dt + (2.0 * a0 + a1) * dt * dt / 6.0;
    velocity += 0.5 * (a0 + a1) * dt;
    rotation = next_rotation;
  }
  const Eigen::Isometry3d truth = drive->sensor_pose(samples.back().stamp) * mount;
  EXPECT_LT((position - truth.translation()).norm(), 0.05);
  EXPECT_LT(rotation_log(rotation.transpose() * truth.linear()).norm(), 1e-4);
  EXPECT_GT((truth.translation() - start.pose.translation()).norm(), 80.0);
}

// A minute at rest: each axis's sample standard deviation is density * sqrt(rate).
TEST(ImuModel, NoiseHasTheDatasheetsDensity) {
  ImuOptions options;
  options.turn_on_bias = false;
  const ImuModel imu(options, 5);
  const std::vector<ImuSample> samples = imu.simulate(*standing(60.0), 0.0, 60.0);
  const ImuSample exact = ImuModel(error_free(), 5).simulate(*standing(1.0), 0.0, 0.0).front();
  Eigen::Vector3d gyro_sum = Eigen::Vector3d::Zero(), accel_sum = Eigen::Vector3d::Zero();
  for (const ImuSample& s : samples) {
    gyro_sum += (s.angular_velocity - exact.angular_velocity).cwiseAbs2();
    accel_sum += (s.linear_acceleration - exact.linear_acceleration).cwiseAbs2();
  }
  const double n = static_cast<double>(samples.size());
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(std::sqrt(gyro_sum(axis) / n) / options.gyro_noise_sigma(), 1.0, 0.1) << axis;
    EXPECT_NEAR(std::sqrt(accel_sum(axis) / n) / options.accel_noise_sigma(), 1.0, 0.1) << axis;
  }
  EXPECT_NEAR(options.gyro_noise_sigma(), 0.0135 * M_PI / 180.0 * std::sqrt(200.0), 1e-12);
}

TEST(ImuModel, TurnOnBiasComesFromTheSeedWithinTheDatasheetsSpread) {
  ImuOptions options;
  options.white_noise = options.bias_random_walk = false;
  const ImuModel first(options, 1), again(options, 1), other(options, 2);
  EXPECT_EQ(first.errors().gyro_turn_on_bias, again.errors().gyro_turn_on_bias);
  EXPECT_NE(first.errors().gyro_turn_on_bias, other.errors().gyro_turn_on_bias);
  const ImuDatasheet& sheet = options.datasheet;
  EXPECT_LE(first.errors().gyro_turn_on_bias.cwiseAbs().maxCoeff(), 3.0 * sheet.gyro_turn_on_bias);
  EXPECT_LE(first.errors().accel_turn_on_bias.cwiseAbs().maxCoeff(),
            3.0 * sheet.accel_turn_on_bias);
  EXPECT_GT(first.errors().accel_turn_on_bias.norm(), 0.0);
  // A constant offset at rest.
  const std::vector<ImuSample> samples = first.simulate(*standing(2.0), 0.0, 2.0);
  const ImuSample exact = ImuModel(error_free(), 1).simulate(*standing(1.0), 0.0, 0.0).front();
  for (const ImuSample& s : samples) {
    EXPECT_LT(
        (s.angular_velocity - exact.angular_velocity - first.errors().gyro_turn_on_bias).norm(),
        1e-12);
  }
}

TEST(ImuModel, TheSameSeedGivesTheSameBytes) {
  const auto drive = smooth_drive(winding(), 3.0);
  const ImuOptions options;
  write_imu_csv(adaptive_lego_loam::test::temp_path("imu_a.csv"),
                ImuModel(options, 9).simulate(*drive, 0.0, 2.0));
  write_imu_csv(adaptive_lego_loam::test::temp_path("imu_b.csv"),
                ImuModel(options, 9).simulate(*drive, 0.0, 2.0));
  write_imu_csv(adaptive_lego_loam::test::temp_path("imu_c.csv"),
                ImuModel(options, 10).simulate(*drive, 0.0, 2.0));
  const std::string a = file_bytes(adaptive_lego_loam::test::temp_path("imu_a.csv"));
  EXPECT_GT(a.size(), 10000u);
  EXPECT_EQ(a, file_bytes(adaptive_lego_loam::test::temp_path("imu_b.csv")));
  EXPECT_NE(a, file_bytes(adaptive_lego_loam::test::temp_path("imu_c.csv")));
}

TEST(ImuModel, BiasRandomWalkFromTheInRunStability) {
  const ImuDatasheet sheet = adis16448();
  EXPECT_NEAR(sheet.gyro_bias_random_walk(), 14.5 * M_PI / 180.0 / 3600.0 / 10.0, 1e-15);
  // Over a long run the bias wanders as sqrt(time): after 100 s by about the stability.
  ImuOptions options;
  options.white_noise = options.turn_on_bias = false;
  options.rate_hz = 10.0;
  double sum = 0.0;
  int runs = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed, ++runs) {
    const std::vector<ImuSample> s = ImuModel(options, seed).simulate(*standing(1.0), 0.0, 100.0);
    sum += (s.back().angular_velocity - s.front().angular_velocity).squaredNorm() / 3.0;
  }
  EXPECT_NEAR(std::sqrt(sum / runs) / sheet.gyro_bias_stability, 1.0, 0.25);
}
