// The paper's KITTI 01 case on the simulated highway, driven along KITTI 01's real trajectory
// (its first 200 scans, 10 -> 25 m/s). Where a stretch has little but guard rails beside it, the
// strict fixed threshold cleans away what constrains the motion along the road and the odometry
// loses it; the adaptive threshold keeps it. Of seeds 1-5, the strict threshold fails on 1 and 5
// (t_err 15 and 126 %), the adaptive one stays under 0.4 % on all five; this test drives seed 5.

#include <gtest/gtest.h>

#include <cstdio>

#include "adaptive_lego_loam/core/pipeline.h"
#include "adaptive_lego_loam/eval/metrics.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "adaptive_lego_loam/sim/trajectory.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

constexpr int kFrames = 200;

Config kitti_config() {
  return load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
}

std::vector<SimFrame> simulate_kitti01_highway() {
  const SensorParams sensor = kitti_config().sensor;
  const std::string data = std::string(TEST_DATA_DIR) + "/kitti_poses/";
  SceneRequest request;
  request.scenario = default_scenario(ScenarioKind::kHighway);
  request.seed = 5;
  request.frames = kFrames;
  request.reach = sensor.max_range;
  request.trajectory_poses =
      camera_poses_to_vehicle_axes(read_kitti_poses(data + "01_frames0-199.txt"));
  request.trajectory_times = read_kitti_times(data + "01_times0-199.txt");
  const GeneratedScene scene = generate_scene(request);
  SimSensorOptions options;
  options.columns = 2083;
  options.motion_distortion = false;  // KITTI ships de-skewed scans
  LidarSimulator simulator(LidarModel(sensor, options), scene.world, scene.trajectory,
                           request.seed);
  std::vector<SimFrame> frames;
  for (int frame = 0; frame < kFrames; ++frame)
    frames.push_back(simulator.render(frame));
  return frames;
}

double translation_error_percent(const Config& config, const std::vector<SimFrame>& frames) {
  Pipeline pipeline(config);
  std::vector<Eigen::Isometry3d> truth;
  for (const SimFrame& frame : frames) {
    Scan scan = frame.scan;
    scan.stamp = frame.time;
    pipeline.process(scan);
    truth.push_back(frames.front().sensor_pose.inverse() * frame.sensor_pose);
  }
  const KittiSegmentError segments = kitti_segment_error(pipeline.trajectory(), truth);
  return segments.translation_percent.value_or(-1.0);
}

}  // namespace

TEST(SimHighway, AdaptiveThresholdFollowsTheRoadWhereTheStrictOneStalls) {
  const std::vector<SimFrame> frames = simulate_kitti01_highway();
  Config adaptive = kitti_config();
  adaptive.ambient.mode = Beta0Mode::kAdaptive;
  Config strict = adaptive;
  strict.ambient.mode = Beta0Mode::kFixed;
  strict.ambient.fixed_beta0_deg = 60.0;
  const double adaptive_error = translation_error_percent(adaptive, frames);
  const double strict_error = translation_error_percent(strict, frames);
  std::printf("[ measured ] t_err adaptive %.3f %%, fixed 60 deg %.3f %%\n", adaptive_error,
              strict_error);
  ASSERT_GE(adaptive_error, 0.0) << "the path must exceed 100 m";
  EXPECT_LT(adaptive_error, 1.0);
  EXPECT_GT(strict_error, 5.0 * adaptive_error);
}
