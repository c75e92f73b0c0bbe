// The smooth trajectory passes through the drive's frame poses (KITTI's, a synthetic path's), and
// its velocity, acceleration and angular rates are its poses' derivatives, the shake included.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/sim/path.h"
#include "adaptive_lego_loam/sim/smooth_trajectory.h"
#include "sim/motion_drives.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

TEST(SmoothTrajectory, PassesThroughKittiPoses) {
  const std::vector<Eigen::Isometry3d> poses = camera_poses_to_vehicle_axes(
      read_kitti_poses(std::string(TEST_DATA_DIR) + "/kitti_seq07/poses.txt"));
  const std::vector<double> times = {0.0, 0.1037, 0.2076, 0.3113, 0.4151};
  auto recorded = std::make_shared<SampledTrajectory>(times, poses, Shake());
  const SmoothTrajectory smooth(recorded, 4, 0.0);
  ASSERT_EQ(smooth.frame_limit(), 5);
  for (int frame = 0; frame < 5; ++frame) {
    const double time = smooth.frame_time(frame);
    EXPECT_EQ(time, recorded->frame_time(frame));
    // Bit for bit the pose the recorded trajectory gives (its own interpolation rounds in the
    // last bits), so that scans rendered at frame times stay the same.
    EXPECT_EQ(smooth.sensor_pose(time).matrix(), recorded->sensor_pose(time).matrix()) << frame;
    EXPECT_TRUE(smooth.sensor_pose(time).isApprox(poses[frame], 1e-15)) << frame;
  }
}

// A synthetic path's frames are where they were: only the poses between them change.
TEST(SmoothTrajectory, KeepsASyntheticDrivesFramePoses) {
  const auto path = std::make_shared<Path>(
      trace_pieces({{60.0, 0.0}, {0.5 * M_PI * 14.0, 1.0 / 14.0}, {60.0, 0.0}}), false);
  const SpeedProfile speed{10.0, 0.1, 20.0, 0.4};
  const Shake shake(ShakeParams(), 7);
  auto drive = std::make_shared<PathTrajectory>(path, speed, 30.0, -1.75, 1.73, shake, 0.1);
  const SmoothTrajectory smooth(drive, 60, 0.0);
  for (int frame = 0; frame < 60; ++frame) {
    const double time = smooth.frame_time(frame);
    EXPECT_EQ(smooth.sensor_pose(time).matrix(), drive->sensor_pose(time).matrix()) << frame;
  }
  // Between frames the curve stays within millimetres of the path's poses.
  for (double time = 0.05; time < 5.9; time += 0.1) {
    EXPECT_LT(
        (smooth.sensor_pose(time).translation() - drive->sensor_pose(time).translation()).norm(),
        0.01)
        << time;
  }
}

TEST(SmoothTrajectory, MotionIsThePosesDerivatives) {
  const Shake shake(ShakeParams(), 3);
  const auto drive = smooth_drive(winding(), 12.0, shake);
  constexpr double h = 1e-4;
  for (double t = 0.5; t < 11.5; t += 0.731) {
    const Kinematics k = drive->motion(t);
    EXPECT_EQ(k.pose.matrix(), drive->sensor_pose(t).matrix());
    const Eigen::Vector3d before = drive->sensor_pose(t - h).translation();
    const Eigen::Vector3d now = drive->sensor_pose(t).translation();
    const Eigen::Vector3d after = drive->sensor_pose(t + h).translation();
    EXPECT_LT((k.velocity - (after - before) / (2.0 * h)).norm(), 1e-5) << t;
    EXPECT_LT((k.acceleration - (after - 2.0 * now + before) / (h * h)).norm(), 2e-2) << t;
    const Eigen::Vector3d rate = rotation_log(drive->sensor_pose(t - h).linear().transpose() *
                                              drive->sensor_pose(t + h).linear()) /
                                 (2.0 * h);
    EXPECT_LT((k.angular_velocity - rate).norm(), 1e-5) << t;
    const Eigen::Vector3d angular_acceleration =
        (drive->motion(t + h).angular_velocity - drive->motion(t - h).angular_velocity) / (2.0 * h);
    EXPECT_LT((k.angular_acceleration - angular_acceleration).norm(), 1e-3) << t;
  }
}

TEST(SmoothTrajectory, OnASinglePoseItStandsThere) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(3.0, -2.0, 1.0);
  const SmoothTrajectory smooth(
      std::make_shared<SampledTrajectory>(std::vector<double>{5.0}, std::vector{pose}, Shake()), 1,
      0.0);
  EXPECT_EQ(smooth.frame_limit(), 1);
  EXPECT_EQ(smooth.sensor_pose(0.0).matrix(), pose.matrix());
  EXPECT_TRUE(smooth.sensor_pose(-0.1).isApprox(pose));
  EXPECT_LT(smooth.motion(0.3).velocity.norm(), 1e-12);
}

TEST(SmoothTrajectory, SampleTimesStepAtTheRateFromTheStart) {
  const std::vector<double> times = sample_times(-0.1, 0.9, 200.0);
  ASSERT_EQ(times.size(), 201u);
  EXPECT_EQ(times.front(), -0.1);
  EXPECT_NEAR(times.back(), 0.9, 1e-12);
  EXPECT_DOUBLE_EQ(times[100], -0.1 + 0.5);
}
