// Each scenario generates, is deterministic, and has the character it claims; the sequence
// writer's output is what KITTI and SemanticKITTI readers expect.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/sim/imu_model.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/sequence_writer.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/motion_drives.h"
#include "sim/sim_requests.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

// A skewed sweep ends at its frame's time, so the first one starts a scan period before the
// first pose: a drive entered at speed goes on as over its first step there, turning as it turns.
TEST(SimTrajectory, BeforeItsFirstPoseASampledDriveKeepsItsFirstMotion) {
  std::vector<Eigen::Isometry3d> poses(2, Eigen::Isometry3d::Identity());
  poses[1].translation() = Eigen::Vector3d(2.5, 0.1, 0.0);
  poses[1].linear() = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const SampledTrajectory drive({10.0, 10.1}, poses, Shake());
  const Eigen::Isometry3d before = drive.sensor_pose(-0.1);
  EXPECT_TRUE(before.translation().isApprox(Eigen::Vector3d(-2.5, -0.1, 0.0), 1e-9));
  EXPECT_NEAR(Eigen::AngleAxisd(before.linear()).angle(), 0.05, 1e-9);
  EXPECT_NEAR(before.linear()(1, 0), -std::sin(0.05), 1e-9);
  EXPECT_TRUE(drive.sensor_pose(0.05).translation().isApprox(Eigen::Vector3d(1.25, 0.05, 0.0)));
  EXPECT_TRUE(drive.sensor_pose(0.3).isApprox(poses[1]));  // after the last: it stands
}

// A rough lane shakes the car's body on its suspension, and the LiDAR and IMU with it: a degree
// or two from one scan to the next (what de-skewing must answer), at the accelerations and rates
// of a body, not the several g and 100 deg/s of a shaker.
TEST(SimTrajectory, ARoughRoadShakesTheSensorAsACarBodyOnItsSuspension) {
  const Eigen::Isometry3d lidar_from_imu = ImuOptions().lidar_from_imu();
  const auto standing_still = [](double) { return Eigen::Isometry3d::Identity(); };
  constexpr double kDegrees = 180.0 / M_PI;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    const auto drive = smooth_drive(standing_still, 30.0, Shake(ShakeParams(), seed));
    double peak_acceleration = 0.0, peak_rate = 0.0;
    std::vector<double> tilt_changes;
    for (int scan = 0; scan < 300; ++scan) {
      const double time = 0.1 * scan;
      const Kinematics lidar = drive->motion(time + 0.037);
      const Kinematics imu = mounted(lidar, lidar_from_imu);
      peak_acceleration =
          std::max({peak_acceleration, lidar.acceleration.norm(), imu.acceleration.norm()});
      peak_rate = std::max(peak_rate, kDegrees * lidar.angular_velocity.norm());
      const Eigen::Vector3d turn = rotation_log(drive->sensor_pose(time).linear().transpose() *
                                                drive->sensor_pose(time + 0.1).linear());
      tilt_changes.push_back(kDegrees * std::hypot(turn.x(), turn.y()));
    }
    EXPECT_GT(peak_acceleration, 1.0) << seed;
    EXPECT_LT(peak_acceleration, 9.81) << seed;  // m/s^2, gravity excluded
    EXPECT_LT(peak_rate, 30.0) << seed;          // deg/s
    std::sort(tilt_changes.begin(), tilt_changes.end());
    EXPECT_GT(tilt_changes[150], 0.4) << seed;  // deg, the median
    EXPECT_LT(tilt_changes[150], 1.2) << seed;
    EXPECT_GT(tilt_changes.back(), 1.0) << seed;
    EXPECT_LT(tilt_changes.back(), 2.5) << seed;
  }
}

TEST(SimTrajectory, TheShakeComesFromItsSeed) {
  const Shake shake(ShakeParams(), 3), again(ShakeParams(), 3), other(ShakeParams(), 4);
  EXPECT_EQ(shake.axes(1.234), again.axes(1.234));
  EXPECT_EQ(shake.at(1.234).matrix(), again.at(1.234).matrix());
  EXPECT_NE(shake.axes(1.234), other.axes(1.234));
  EXPECT_EQ(Shake().axes(1.234), Eigen::Matrix3d::Zero());  // a smooth ride
}

TEST(SimTrajectory, KittiGroundTruthDrivesTheSensor) {
  const std::vector<Eigen::Isometry3d> camera =
      adaptive_lego_loam::read_kitti_poses(std::string(TEST_DATA_DIR) + "/kitti_seq07/poses.txt");
  const std::vector<Eigen::Isometry3d> vehicle = camera_poses_to_vehicle_axes(camera);
  SceneRequest request = request_for(ScenarioKind::kUrban, 3, 4);
  request.trajectory_poses = vehicle;
  for (std::size_t i = 0; i < vehicle.size(); ++i)
    request.trajectory_times.push_back(0.1 * i);
  const GeneratedScene scene = generate_scene(request);
  const Eigen::Isometry3d first = scene.trajectory->sensor_pose(0.0);
  for (int frame = 1; frame < 4; ++frame) {
    const Eigen::Isometry3d relative = vehicle[0].inverse() * vehicle[frame];
    // Camera z (forward) became x, camera x (right) became -y, camera y (down) became -z.
    const Eigen::Vector3d in_camera = (camera[0].inverse() * camera[frame]).translation();
    EXPECT_NEAR(relative.translation().x(), in_camera.z(), 1e-9);
    EXPECT_NEAR(relative.translation().y(), -in_camera.x(), 1e-9);
    EXPECT_NEAR(relative.translation().z(), -in_camera.y(), 1e-9);
    EXPECT_GT(relative.translation().x(), 0.05 * frame);  // KITTI 07 starts slowly forward
    // The sensor drives it, its positions smoothed by millimetres (kRecordedCutoffHz).
    const Eigen::Isometry3d driven =
        first.inverse() * scene.trajectory->sensor_pose(scene.trajectory->frame_time(frame));
    EXPECT_LT((driven.translation() - relative.translation()).norm(), 0.01) << frame;
    EXPECT_TRUE(driven.linear().isApprox(relative.linear(), 1e-9)) << frame;
  }
  request.frames = 6;
  EXPECT_THROW(generate_scene(request), std::invalid_argument);
}
