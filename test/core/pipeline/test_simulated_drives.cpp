// The whole pipeline on simulated sequences with exact ground truth: a known trajectory is
// recovered and a loop is closed; the ambient filter finds the tunnel and the highway more
// degenerate than the city; on a highway the adaptive threshold keeps the odometry on the road
// where a strict fixed one stalls.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/eval/metrics.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "adaptive_lego_loam/sim/trajectory.h"
#include "support/sanitizers.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

Config kitti_config() {
  return load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
}

SceneRequest scene_request(ScenarioKind kind, uint64_t seed, int frames) {
  SceneRequest request;
  request.scenario = default_scenario(kind);
  request.seed = seed;
  request.frames = frames;
  request.reach = kitti_config().sensor.max_range;
  return request;
}

// KITTI's HDL-64E (2083 firings a turn, de-skewed scans as KITTI ships them) driving the scene of
// `request`, of which the frames `first`, `first` + `step`, ... before `rendered` are simulated (a
// loop's path wraps round: frames past `request.frames` go round again).
std::vector<SimFrame> simulate(const SceneRequest& request, int rendered, int step = 1,
                               int first = 0) {
  const GeneratedScene scene = generate_scene(request);
  SimSensorOptions options;
  options.columns = 2083;
  options.motion_distortion = false;
  LidarSimulator simulator(LidarModel(kitti_config().sensor, options), scene.world,
                           scene.trajectory, request.seed);
  std::vector<SimFrame> out;
  for (int frame = first; frame < rendered; frame += step)
    out.push_back(simulator.render(frame));
  return out;
}

struct Drive {
  std::vector<Eigen::Isometry3d> estimate, truth;  // truth relative to the first frame
  int loops = 0;
};

Drive drive(const Config& config, const std::vector<SimFrame>& frames) {
  Pipeline pipeline(config);
  Drive out;
  for (const SimFrame& frame : frames) {
    Scan scan = frame.scan;
    scan.stamp = frame.time;
    out.loops += pipeline.process(scan).loop_closed;
    out.truth.push_back(frames.front().sensor_pose.inverse() * frame.sensor_pose);
  }
  out.estimate = pipeline.trajectory();
  return out;
}

}  // namespace

TEST(SimOdometry, LoopTrajectoryRecoveredAndClosed) {
  // A 160 m urban loop in 20 s, and on past the start for 2.5 s: loops are looked for once a
  // second (an attempt runs a bounded piece a scan, kitti.yaml's for about 10 scans), and only
  // from past the start does the candidate's map (the first keyframes and those after them)
  // cover what the scan sees. Loops are looked for 15 s back (LeGO-LOAM: 30 s) to keep the test
  // short.
  Config config = kitti_config();
  config.loop_closure.min_time_gap = 15.0;
  const auto [estimate, truth, loops] =
      drive(config, simulate(scene_request(ScenarioKind::kLoop, 2, 200), 225));
  const KittiSegmentError segments = kitti_segment_error(estimate, truth);
  ASSERT_TRUE(segments.translation_percent.has_value()) << "the path must exceed 100 m";
  EXPECT_LT(*segments.translation_percent, 2.0);
  EXPECT_GE(loops, 1) << "the path returns to its start: a loop must close";
  const double end_error = (estimate.back().translation() - truth.back().translation()).norm();
  EXPECT_LT(end_error, 0.5);
  const double ate = absolute_trajectory_error(estimate, truth).rmse_m;
  std::printf(
      "[ measured ] t_err %.3f %%, r_err %.3f deg/100 m, %d loop(s), end error %.3f m, "
      "ATE %.3f m\n",
      *segments.translation_percent, *segments.rotation_deg_per_100m, loops, end_error, ate);
  // The loop edges must be as good as the odometry between their ends, a few centimetres here:
  // an edge further off pulls the trajectory apart instead of together.
  EXPECT_LT(ate, 0.035);
}

// A VLP-16 drive with raw, skewed sweeps: the pipeline de-skews each to its end and reports the
// pose there, which is the frame's truth (the simulator ends a sweep at the frame's time, as a
// Velodyne driver stamps a scan with its last packet). Through a bend of about 5 deg a scan the
// heading then follows the truth scan by scan; a sweep posed at its start would be a scan's turn
// off.
TEST(SimOdometry, ASkewedSweepIsPosedWhereItEnds) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/vlp16.yaml");
  SceneRequest request;
  request.scenario = named_scenario("busy_street");
  request.seed = 1;
  request.frames = 300;
  request.reach = config.sensor.max_range;
  const GeneratedScene scene = generate_scene(request);
  SimSensorOptions options;
  options.columns = config.sensor.columns;
  options.motion_distortion = true;
  LidarSimulator simulator(LidarModel(config.sensor, options), scene.world, scene.trajectory,
                           request.seed);
  std::vector<SimFrame> frames;
  for (int frame = 0; frame < 62; ++frame)
    frames.push_back(simulator.render(frame));
  const Drive result = drive(config, frames);
  auto yaw_deg = [](const Eigen::Isometry3d& pose) {
    return std::atan2(pose(1, 0), pose(0, 0)) * 180.0 / M_PI;
  };
  int turning = 0;
  double heading_error = 0.0;
  for (std::size_t i = 1; i < result.truth.size(); ++i) {
    if (std::abs(yaw_deg(result.truth[i - 1].inverse() * result.truth[i])) < 2.0) continue;
    ++turning;
    heading_error += std::abs(yaw_deg(result.truth[i].inverse() * result.estimate[i]));
  }
  ASSERT_GE(turning, 8) << "the premise: the drive turns more than 2 deg a scan for a while";
  heading_error /= turning;
  std::printf("[ measured ] %d scans in the bend, mean heading error %.2f deg\n", turning,
              heading_error);
  EXPECT_LT(heading_error, 1.0);
}

// Mean mu over every 10th of 200 frames of seeds 1-3 (HDL-64E); in the bare tunnel over every
// 10th of frames 150-299, well inside it. Measured: urban 0.63, highway 0.90, bare tunnel 0.92.
// The highway's stretches differ: along concrete barriers, noise walls, berms and cuttings mu is
// 0.85-0.95; along guard rails alone it falls to 0.5 or below, as a rail's few rows break into
// small depth clusters and the skeleton keeps little more than nearby cars, posts and signs.
TEST(SimOdometry, HighwayAndTunnelAreMoreDegenerateThanUrban) {
  ALEGO_SKIP_WHEN_SANITIZED();
  const Config config = kitti_config();
  auto mean_mu = [&](const std::string& scenario) {
    AmbientFilter filter(config);
    AmbientFilterResult result;
    double sum = 0.0;
    int valid = 0;
    const bool tunnel = scenario == "bare_tunnel";
    const int frames = tunnel ? 300 : 200;
    for (uint64_t seed = 1; seed <= 3; ++seed) {
      SceneRequest request = scene_request(ScenarioKind::kUrban, seed, frames);
      request.scenario = named_scenario(scenario);
      for (const SimFrame& frame : simulate(request, frames, 10, tunnel ? 150 : 0)) {
        filter.reset();
        filter.process(frame.scan, result);
        if (!result.degeneration.valid) continue;
        sum += result.degeneration.mu;
        ++valid;
      }
    }
    return valid > 0 ? sum / valid : -1.0;
  };
  const double urban = mean_mu("urban");
  const double highway = mean_mu("highway");
  const double tunnel = mean_mu("bare_tunnel");
  std::printf("[ measured ] mean mu: urban %.3f, highway %.3f, tunnel %.3f\n", urban, highway,
              tunnel);
  ASSERT_GE(urban, 0.0);
  EXPECT_GT(tunnel, urban + 0.1);
  EXPECT_GT(highway, urban + 0.1);
  EXPECT_GT(tunnel, 0.85);
}

// Foliage breaks up under the skeleton's strict depth clustering and walls hold together: the
// skeleton is a far smaller share of the clustered points among trees and planted verges than in
// a street of buildings. mu cannot tell a planted highway from a city street (both about 0.55 on
// the HDL-64E); this share can. Guard rails break up too, at grazing incidence, but their
// fragments lie on smooth lines where leaves' do not: counted as structure, they lift the bare
// highway's share above the planted one's (ambient_filter.fragment_smoothness_floor).
TEST(SimOdometry, TheSkeletonIsASmallShareOfFoliageAndRailsFragmentsAreSmooth) {
  ALEGO_SKIP_WHEN_SANITIZED();
  const Config config = kitti_config();
  struct Medians {
    double skeleton_share, smoothness, structure_share;
  };
  auto median = [](std::vector<double>& values) {
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values.empty() ? -1.0 : values[values.size() / 2];
  };
  auto medians = [&](const ScenarioParams& scenario) {
    AmbientFilter filter(config);
    AmbientFilterResult result;
    std::vector<double> skeleton_shares, smoothness, structure_shares;
    for (uint64_t seed = 1; seed <= 2; ++seed) {
      SceneRequest request = scene_request(ScenarioKind::kUrban, seed, 200);
      request.scenario = scenario;
      for (const SimFrame& frame : simulate(request, 200, 20)) {
        filter.process(frame.scan, result);
        if (result.euclidean_points == 0) continue;
        skeleton_shares.push_back(result.skeleton_share());
        smoothness.push_back(result.fragment_smoothness);
        structure_shares.push_back(result.structure_share);
      }
    }
    return Medians{median(skeleton_shares), median(smoothness), median(structure_shares)};
  };
  const Medians urban = medians(default_scenario(ScenarioKind::kUrban));
  const Medians vegetation = medians(default_scenario(ScenarioKind::kVegetation));
  const Medians planted = medians(named_scenario("green_highway"));
  const Medians bare = medians(default_scenario(ScenarioKind::kHighway));
  for (const auto& [name, m] : {std::pair{"urban", urban},
                                {"vegetation", vegetation},
                                {"planted highway", planted},
                                {"bare highway", bare}}) {
    std::printf(
        "[ measured ] %s: median skeleton share %.3f, fragment smoothness %.3f, "
        "structure share %.3f\n",
        name, m.skeleton_share, m.smoothness, m.structure_share);
  }
  ASSERT_GT(urban.skeleton_share, 0.0);
  EXPECT_LT(vegetation.skeleton_share, urban.skeleton_share / 3.0);
  EXPECT_LT(planted.skeleton_share, urban.skeleton_share / 2.0);
  EXPECT_GT(bare.smoothness, vegetation.smoothness + 0.1);
  EXPECT_GT(bare.smoothness, planted.smoothness + 0.05);
  EXPECT_GT(bare.structure_share, planted.structure_share + 0.1);
  EXPECT_LT(vegetation.structure_share, urban.structure_share / 3.0);
}

// The paper's KITTI 01 case on the simulated highway, driven along KITTI 01's real trajectory
// (its first 200 scans, 10 -> 25 m/s). Beside the road there is little but guard rails and a
// few shrubs and trees, which constrain the motion along it; the strict fixed threshold drops
// much of them and drifts more than the adaptive one, which sees the degenerate road and keeps
// them.
TEST(SimOdometry, AdaptiveThresholdDriftsLessOnTheHighwayThanTheStrictOne) {
  ALEGO_SKIP_WHEN_SANITIZED();
  const int frames = 200;
  const std::string data = std::string(TEST_DATA_DIR) + "/kitti_poses/";
  SceneRequest request = scene_request(ScenarioKind::kHighway, 5, frames);
  request.trajectory_poses =
      camera_poses_to_vehicle_axes(read_kitti_poses(data + "01_frames0-199.txt"));
  request.trajectory_times = read_kitti_times(data + "01_times0-199.txt");
  const std::vector<SimFrame> scans = simulate(request, frames);
  auto translation_error_percent = [&](const Config& config) {
    const Drive result = drive(config, scans);
    return kitti_segment_error(result.estimate, result.truth).translation_percent.value_or(-1.0);
  };
  Config adaptive = kitti_config();
  adaptive.ambient.mode = Beta0Mode::kAdaptive;
  Config strict = adaptive;
  strict.ambient.mode = Beta0Mode::kFixed;
  strict.ambient.fixed_beta0_deg = 60.0;
  const double adaptive_error = translation_error_percent(adaptive);
  const double strict_error = translation_error_percent(strict);
  std::printf("[ measured ] highway t_err adaptive %.3f %%, fixed 60 deg %.3f %%\n", adaptive_error,
              strict_error);
  ASSERT_GE(adaptive_error, 0.0) << "the path must exceed 100 m";
  EXPECT_LT(adaptive_error, 1.0);
  EXPECT_GT(strict_error, adaptive_error);
}

// A drive that starts at 23-26 m/s beside guard rails (KITTI 01's frames 120-199 on the simulated
// highway, whose verges are mostly open): the first pair of scans has no motion to start from.
// From a zero guess, every correspondence weighed the same, it settles on an alias of the posts
// (2 m apart) and lags for scans; the start search finds the motion from the first scan, with or
// without kitti.yaml's range weighting. (Beside the green highway's planted verges, as dense as
// KITTI's, even the zero guess finds the motion, as on the real KITTI 01.)
TEST(SimOdometry, AHighwayEnteredAtSpeedIsTrackedFromItsFirstScan) {
  ALEGO_SKIP_WHEN_SANITIZED();
  const int first = 120, frames = 80;
  const std::string data = std::string(TEST_DATA_DIR) + "/kitti_poses/";
  const std::vector<Eigen::Isometry3d> poses =
      camera_poses_to_vehicle_axes(read_kitti_poses(data + "01_frames0-199.txt"));
  const std::vector<double> times = read_kitti_times(data + "01_times0-199.txt");
  SceneRequest request = scene_request(ScenarioKind::kHighway, 7, frames);
  request.trajectory_poses.assign(poses.begin() + first, poses.begin() + first + frames);
  for (int i = first; i < first + frames; ++i)
    request.trajectory_times.push_back(times[i] - times[first]);
  const std::vector<SimFrame> scans = simulate(request, frames);
  auto run = [&](double start_search_max_speed, double range_weight_fit_error) {
    Config config = kitti_config();
    config.odometry.start_search_max_speed = start_search_max_speed;
    config.odometry.range_weight_fit_error = range_weight_fit_error;
    const Drive result = drive(config, scans);
    const double first_step = ((result.truth[0].inverse() * result.truth[1]).inverse() *
                               (result.estimate[0].inverse() * result.estimate[1]))
                                  .translation()
                                  .norm();
    return std::make_pair(
        kitti_segment_error(result.estimate, result.truth).translation_percent.value_or(-1.0),
        first_step);
  };
  const double range_weighting = kitti_config().odometry.range_weight_fit_error;
  ASSERT_GT(range_weighting, 0.0) << "kitti.yaml weighs correspondences by range";
  const auto [searched, searched_first] = run(40.0, range_weighting);
  const auto [search_only, search_only_first] = run(40.0, 0.0);
  const auto [from_zero, from_zero_first] = run(0.0, 0.0);
  std::printf(
      "[ measured ] entered at speed: t_err %.3f %% (first scan off by %.2f m); start search "
      "without range weighting %.3f %% (%.2f m); neither %.3f %% (%.2f m)\n",
      searched, searched_first, search_only, search_only_first, from_zero, from_zero_first);
  ASSERT_GE(searched, 0.0) << "the path must exceed 100 m";
  EXPECT_LT(searched, 1.0);
  EXPECT_LT(searched_first, 0.2);
  EXPECT_LT(search_only, 1.0);
  EXPECT_LT(search_only_first, 0.2);
  EXPECT_GT(from_zero_first, 1.0) << "the premise: from zero the start settles on an alias";
}

// The featureless tunnel on the LiDAR alone (kitti.yaml, 240 scans, tuning seed 4): its smooth
// walls fix nothing along the road, and their rings, which stay where they are in the sensor
// frame, pull the odometry toward standing still, about a tenth of the speed a scan, until the
// estimate stops inside (0.63 of the true path). With the follow test (odometry.follow_test_shift)
// the scans that follow a shifted guess keep the motion along the road at the guess, and the
// estimate keeps going (0.94).
TEST(SimOdometry, TheFollowTestKeepsTheBareTunnelGoing) {
  ALEGO_SKIP_WHEN_SANITIZED();
  SceneRequest request = scene_request(ScenarioKind::kUrban, 4, 240);
  request.scenario = named_scenario("bare_tunnel");
  const std::vector<SimFrame> frames = simulate(request, 240);
  const auto reach = [&](double shift) {
    Config config = kitti_config();
    config.odometry.follow_test_shift = shift;
    const Drive result = drive(config, frames);
    return end_drift(result.estimate, result.truth).reach_ratio.value_or(0.0);
  };
  const double without = reach(0.0), with = reach(0.1);
  std::printf(
      "[ measured ] bare tunnel, estimated over true path length: %.3f without the "
      "follow test, %.3f with it\n",
      without, with);
  EXPECT_LT(without, 0.8);
  EXPECT_GT(with, 0.9);
  EXPECT_LT(with, 1.3);
}
