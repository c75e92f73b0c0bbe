// Localization on a saved map: a simulated VLP-16 drive builds the map, which is saved and loaded
// again; a second drive through the same scene (other noise, other moving cars and walkers,
// started further along the road and 1 m and 5 deg off) is tracked against it from its first
// de-skewed scan; a drive through another scene is reported lost.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/io/map_files.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

constexpr int kMapFrames = 120;
constexpr int kStartFrame = 20;  // the second drive starts here on the map drive's path

Config vlp16_config() {
  return load_config(std::string(CONFIG_DIR) + "/vlp16.yaml");
}

// Frames [first, last) of the urban scene `scene_seed` driven with `seed` (noise, moving
// objects), VLP-16 with motion distortion as lidar_sim makes it.
std::vector<SimFrame> drive(uint64_t scene_seed, uint64_t seed, int first, int last) {
  const Config config = vlp16_config();
  SceneRequest request;
  request.scenario = default_scenario(ScenarioKind::kUrban);
  request.seed = seed;
  request.scene_seed = scene_seed;
  request.frames = kMapFrames;
  request.frame_period = config.sensor.scan_period;
  request.reach = config.sensor.max_range;
  const GeneratedScene scene = generate_scene(request);
  LidarSimulator simulator(LidarModel(config.sensor, SimSensorOptions()), scene.world,
                           scene.trajectory, seed);
  std::vector<SimFrame> frames;
  for (int frame = first; frame < last; ++frame)
    frames.push_back(simulator.render(frame));
  return frames;
}

Scan scan_of(const SimFrame& frame) {
  Scan scan = frame.scan;
  scan.stamp = frame.time;
  return scan;
}

struct MapRun {
  std::vector<Eigen::Isometry3d> poses;  // the map drive's mapped poses (the map frame)
  Eigen::Isometry3d first_truth;         // its first frame's true pose
  std::string folder;
};

// Maps scene 7 with seed 1, saves the map and keeps the poses; once for every test.
const MapRun& map_run() {
  static const MapRun run = [] {
    MapRun out;
    const std::vector<SimFrame> frames = drive(7, 1, 0, kMapFrames);
    Pipeline pipeline(vlp16_config());
    for (const SimFrame& frame : frames)
      pipeline.process(scan_of(frame));
    out.poses = pipeline.trajectory();
    out.first_truth = frames.front().sensor_pose;
    out.folder = test::temp_path("localization_map");
    std::filesystem::remove_all(out.folder);
    MapDescription description{"vlp16.yaml", "vlp16", "test_localization", kMapFrames};
    save_map(out.folder, pipeline.keyframes(), description, vlp16_config());
    return out;
  }();
  return run;
}

struct Localized {
  std::vector<Eigen::Isometry3d> poses;
  std::vector<LocalizationState> states;
  int most_own_keyframes = 0;  // the drive's own keyframes held at once, at most
};

Localized localize(const std::vector<SimFrame>& frames, const Eigen::Isometry3d& start) {
  const SavedMap map = load_map(map_run().folder);
  Pipeline pipeline(vlp16_config(), map.keyframes, start);
  Localized out;
  for (const SimFrame& frame : frames) {
    const FrameResult& result = pipeline.process(scan_of(frame));
    EXPECT_TRUE(result.localization.has_value());
    out.poses.push_back(result.pose);
    out.states.push_back(result.localization ? result.localization->state
                                             : LocalizationState::kAligning);
    const int own = static_cast<int>(pipeline.keyframes().size() - map.keyframes.size());
    out.most_own_keyframes = std::max(out.most_own_keyframes, own);
  }
  return out;
}

Eigen::Isometry3d offset(double metres, double yaw_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(metres, 0.0, 0.0);
  pose.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  return pose;
}

// The second drive through scene 7 (seed 2), from kStartFrame on, started where the map put this
// place on its own drive, moved 1 m and 5 deg; once for every test.
const Localized& second_drive() {
  static const Localized localized = localize(drive(7, 2, kStartFrame, kMapFrames),
                                              map_run().poses[kStartFrame] * offset(1.0, 5.0));
  return localized;
}

}  // namespace

TEST(Localization, SecondDriveThroughTheSceneIsTrackedWhereTheMapPutsIt) {
  const MapRun& map = map_run();
  const Localized& localized = second_drive();

  // The first sweep, raw, is not aligned; the next ones are, until one fits the map.
  int first_tracked = -1;
  for (std::size_t i = 0; i < localized.states.size(); ++i) {
    if (localized.states[i] == LocalizationState::kTracking) {
      first_tracked = static_cast<int>(i);
      break;
    }
    EXPECT_EQ(localized.states[i], LocalizationState::kAligning) << "scan " << i;
  }
  ASSERT_GE(first_tracked, 1);
  EXPECT_LE(first_tracked, 3);
  for (std::size_t i = first_tracked; i < localized.states.size(); ++i)
    EXPECT_EQ(localized.states[i], LocalizationState::kTracking) << "scan " << i;

  // Both drives follow the same path, so each tracked scan belongs where the map drive's own
  // pose at that place is: the error against the map, not the map's own drift.
  double squared_sum = 0.0;
  double largest = 0.0;
  for (std::size_t i = first_tracked; i < localized.poses.size(); ++i) {
    const double error =
        (localized.poses[i].translation() - map.poses[kStartFrame + i].translation()).norm();
    squared_sum += error * error;
    largest = std::max(largest, error);
  }
  const double rms = std::sqrt(squared_sum / double(localized.poses.size() - first_tracked));
  std::printf(
      "[ measured ] first tracked scan %d, position error against the map RMS %.3f m, "
      "max %.3f m\n",
      first_tracked, rms, largest);
  EXPECT_LT(rms, 0.2);
  EXPECT_LT(largest, 0.5);
}

TEST(Localization, ADriveThroughAnotherSceneIsReportedLost) {
  const Localized localized = localize(drive(8, 2, 0, 40), Eigen::Isometry3d::Identity());
  int lost = 0;
  for (std::size_t i = 0; i < localized.states.size(); ++i) {
    EXPECT_NE(localized.states[i], LocalizationState::kTracking) << "scan " << i;
    lost += localized.states[i] == LocalizationState::kLost;
  }
  EXPECT_GT(lost, 30) << "lost within lost_after_scans scans, and reported on every scan after";
}

TEST(Localization, TheDrivesOwnKeyframesStayFewHoweverFarItGoes) {
  // About a keyframe a metre over 100 scans; only the newest (matched with the map's, or kept out
  // of the local map for a while) stay, so localization holds no more after hours than now.
  const Config config = vlp16_config();
  const int bound =
      config.localization.recent_keyframes + config.mapping.local_map_lag_keyframes + 1;
  EXPECT_LE(second_drive().most_own_keyframes, bound);
  EXPECT_GT(map_run().poses.back().translation().norm(), 50.0) << "far more keyframes than kept";
}

TEST(Localization, NoKeyframeOfTheDriveJoinsTheSavedMap) {
  const MapRun& map = map_run();
  const SavedMap saved = load_map(map.folder);
  Pipeline pipeline(vlp16_config(), saved.keyframes, map.poses[kStartFrame]);
  for (const SimFrame& frame : drive(7, 2, kStartFrame, kStartFrame + 30))
    pipeline.process(scan_of(frame));
  // The map's keyframes keep their poses and clouds; the drive's own keep only the newest few.
  const std::vector<Keyframe>& keyframes = pipeline.keyframes();
  ASSERT_GE(keyframes.size(), saved.keyframes.size());
  for (std::size_t i = 0; i < saved.keyframes.size(); ++i) {
    EXPECT_TRUE(keyframes[i].pose.isApprox(saved.keyframes[i].pose, 1e-12)) << "keyframe " << i;
    EXPECT_EQ(keyframes[i].has_clouds(), saved.keyframes[i].has_clouds()) << "keyframe " << i;
  }
  int own_with_clouds = 0;
  for (std::size_t i = saved.keyframes.size(); i < keyframes.size(); ++i)
    own_with_clouds += keyframes[i].has_clouds();
  EXPECT_LE(own_with_clouds, vlp16_config().localization.recent_keyframes);
}
