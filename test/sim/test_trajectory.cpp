// Each scenario generates, is deterministic, and has the character it claims; the sequence
// writer's output is what KITTI and SemanticKITTI readers expect.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/sequence_writer.h"
#include "adaptive_lego_loam/sim/simulator.h"
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
