#include <gtest/gtest.h>

#include <random>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/eval/metrics.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_files.h"

using namespace adaptive_lego_loam;

namespace {

const std::string kSequence = std::string(TEST_DATA_DIR) + "/kitti_seq07";

std::vector<Scan> kitti_scans() {
  const std::vector<double> times = read_kitti_times(kSequence + "/times.txt");
  const auto files = list_scan_files(kSequence + "/velodyne");
  std::vector<Scan> scans;
  for (std::size_t i = 0; i < files.size(); ++i) {
    scans.push_back(read_kitti_bin(files[i]));
    scans.back().stamp = times[i];
  }
  return scans;
}

// With `threads` > 1 each scan is processed knowing the next, as run_sequence does.
std::vector<Eigen::Isometry3d> run(const Config& config, std::vector<FrameResult>* frames = nullptr,
                                   int threads = 1) {
  Pipeline pipeline(config);
  pipeline.set_threads(threads);
  const std::vector<Scan> scans = kitti_scans();
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const Scan* next = threads > 1 && i + 1 < scans.size() ? &scans[i + 1] : nullptr;
    const FrameResult& result = pipeline.process(scans[i], next);
    if (frames) frames->push_back(result);
  }
  return pipeline.trajectory();
}

std::vector<Eigen::Isometry3d> lidar_ground_truth() {
  return camera_to_lidar_poses(read_kitti_poses(kSequence + "/poses.txt"),
                               read_kitti_calib_tr(kSequence + "/calib.txt"));
}

}  // namespace

TEST(Pipeline, KittiSeq07PerFrameErrorUnder3cm) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  std::vector<FrameResult> frames;
  const auto estimate = run(config, &frames);
  const auto truth = lidar_ground_truth();
  ASSERT_EQ(estimate.size(), truth.size());
  const RelativePoseError rpe = relative_pose_error(estimate, truth);
  for (std::size_t i = 0; i < rpe.translation_m.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i + 1));
    EXPECT_LT(rpe.translation_m[i], 0.03);
    EXPECT_LT(rpe.rotation_deg[i], 0.5);
    EXPECT_TRUE(frames[i + 1].odometry.registered);
  }
  // Mapping ran on every scan after the first.
  for (std::size_t i = 1; i < frames.size(); ++i)
    EXPECT_TRUE(frames[i].mapping.matched);
  std::printf("RPE per frame (m):");
  for (double e : rpe.translation_m)
    std::printf(" %.4f", e);
  std::printf("\nATE RMSE %.4f m\n", absolute_trajectory_error(estimate, truth).rmse_m);
}

TEST(Pipeline, TwoStepAndJointOdometryBothTrack) {
  Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  config.mapping.enabled = false;  // the odometry alone
  const auto truth = lidar_ground_truth();
  for (OdometryMode mode : {OdometryMode::kTwoStep, OdometryMode::kJoint}) {
    config.odometry.mode = mode;
    const RelativePoseError rpe = relative_pose_error(run(config), truth);
    SCOPED_TRACE(mode == OdometryMode::kJoint ? "joint" : "two-step");
    EXPECT_LT(*rpe.translation_rmse_m, 0.05);
    std::printf("%s odometry RPE RMSE %.4f m\n",
                mode == OdometryMode::kJoint ? "joint" : "two-step", *rpe.translation_rmse_m);
  }
}

TEST(Pipeline, SameInputGivesIdenticalPoses) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  const auto first = run(config), second = run(config);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_TRUE(first[i].matrix() == second[i].matrix()) << "frame " << i;
  }
}

// Threads change when the work is done, not what it computes: the first pair's start search (its
// guesses shared), every scan's filter (run ahead) and the searches give the same bits.
TEST(Pipeline, MoreThreadsGiveTheSamePosesToTheLastBit) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  std::vector<FrameResult> one_thread;
  const auto reference = run(config, &one_thread);
  for (int threads : {2, 3}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    std::vector<FrameResult> frames;
    const auto poses = run(config, &frames, threads);
    ASSERT_EQ(poses.size(), reference.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
      SCOPED_TRACE("frame " + std::to_string(i));
      EXPECT_TRUE(poses[i].matrix() == reference[i].matrix());
      EXPECT_TRUE(frames[i].odometry_pose.matrix() == one_thread[i].odometry_pose.matrix());
      EXPECT_TRUE(frames[i].mapping.information == one_thread[i].mapping.information);
      EXPECT_EQ(frames[i].mapping.plane_matches, one_thread[i].mapping.plane_matches);
      EXPECT_EQ(frames[i].flat, one_thread[i].flat);
    }
  }
}

TEST(Pipeline, AScanOtherThanTheAnnouncedNextIsRefused) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  const std::vector<Scan> scans = kitti_scans();
  Pipeline pipeline(config);
  pipeline.set_threads(2);
  pipeline.process(scans[0], &scans[1]);
  EXPECT_THROW(pipeline.process(scans[2], &scans[3]), std::logic_error);
}

// KITTI 07 starts at about 0.9 m/s (0.09 m a scan). With the odometry's speed bound below that,
// each registered motion is rejected as a registration that ran away: the prediction (standing
// still) is kept and each rejection is reported; with the bound above it, none is.
TEST(Pipeline, AnOdometryMotionFasterThanMaxSpeedIsRejectedAndThePredictionKept) {
  Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  config.mapping.enabled = false;  // the odometry alone, as mapping would correct it
  for (double max_speed : {0.5, 2.0}) {
    SCOPED_TRACE("max_speed " + std::to_string(max_speed));
    config.odometry.max_speed = max_speed;
    std::vector<FrameResult> frames;
    const auto estimate = run(config, &frames);
    const bool rejecting = max_speed < 0.9;
    for (std::size_t i = 1; i < frames.size(); ++i) {
      SCOPED_TRACE("frame " + std::to_string(i));
      EXPECT_TRUE(frames[i].odometry.registered);
      EXPECT_EQ(frames[i].odometry.rejected, rejecting);
      EXPECT_EQ(estimate[i].translation().norm() < 1e-9, rejecting);
    }
  }
}

// Between real scans: an empty scan (a .bin of 0 bytes) and one of two million points (a driver
// gone wrong, or a merge of many sweeps). The empty one gets a predicted pose and is counted; the
// big one fills the range image, counts what it could not place, and is processed; the scans after
// them are tracked.
TEST(Pipeline, AnEmptyScanAndOneOfTwoMillionPointsAreProcessedAndCounted) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  Pipeline pipeline(config);
  const std::vector<double> times = read_kitti_times(kSequence + "/times.txt");
  const auto files = list_scan_files(kSequence + "/velodyne");
  std::mt19937 random(5);
  std::uniform_real_distribution<float> coordinate(-60.f, 60.f), height(-2.f, 3.f);
  int frames = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    Scan scan = read_kitti_bin(files[i]);
    scan.stamp = times[i];
    EXPECT_TRUE(pipeline.process(scan).valid_scan) << "scan " << i;
    ++frames;
    if (i != 1) continue;
    Scan empty = parse_kitti_bin("", "empty.bin");
    empty.stamp = times[i] + 0.03;
    EXPECT_FALSE(pipeline.process(empty).valid_scan);
    ++frames;
    Scan huge;
    huge.stamp = times[i] + 0.06;
    huge.points.resize(2'000'000);
    for (ScanPoint& p : huge.points) {
      p.x = coordinate(random);
      p.y = coordinate(random);
      p.z = height(random);
    }
    EXPECT_TRUE(pipeline.process(huge).valid_scan);
    const ProjectionStats& stats = pipeline.filter_result().segmentation.image.stats();
    EXPECT_EQ(stats.input_points, 2'000'000);
    EXPECT_LE(stats.projected, config.sensor.rows * config.sensor.columns);
    EXPECT_EQ(stats.projected + stats.collisions + stats.out_of_range + stats.outside_rows +
                  stats.non_finite,
              2'000'000);
    ++frames;
  }
  EXPECT_EQ(static_cast<int>(pipeline.trajectory().size()), frames);
}

TEST(Pipeline, TheWeakestDirectionIsDegenerateBeyondTheThresholdAndSaysWhatHeldIt) {
  MappingParams params;
  params.degenerate_translation_sigma = 0.1;
  MapMatchResult match;
  match.matched = true;
  match.information = Matrix6d::Identity() * 1e6;
  match.information(3, 3) = 1.0;  // along the sensor's x: 1 m
  WeakestDirection weakest = weakest_direction(match, std::nullopt, params);
  EXPECT_GT(std::fabs(weakest.direction.x()), 0.999);
  EXPECT_NEAR(weakest.sigma, 1.0, 1e-6);
  EXPECT_TRUE(weakest.degenerate);
  EXPECT_FALSE(weakest.held);
  match.odometry_held = true;  // the follow test's hold, LiDAR-only
  EXPECT_EQ(weakest_direction(match, std::nullopt, params).held_by, "the motion model");
  match.motion_prior = true;
  match.prior_from_wheel = true;
  EXPECT_TRUE(weakest_direction(match, std::nullopt, params).held);
  EXPECT_EQ(weakest_direction(match, std::nullopt, params).held_by, "the wheel odometry");
  match.prior_from_imu = true;
  EXPECT_EQ(weakest_direction(match, std::nullopt, params).held_by,
            "the IMU and the wheel odometry");
  // Well fixed everywhere, but the scene says y is its weak direction, fully degenerate: the
  // correspondences along it are not the scene's.
  match.information(3, 3) = 1e6;
  EXPECT_FALSE(weakest_direction(match, std::nullopt, params).degenerate);
  const WeakestDirection along_y =
      weakest_direction(match, SceneDegeneration{Eigen::Vector3d::UnitY(), 1.0}, params);
  EXPECT_TRUE(along_y.degenerate);
  EXPECT_GT(std::fabs(along_y.direction.y()), 0.999);
}

// The first scan defines the map frame: its pose is exact. A scan not matched keeps its guess,
// known to nothing; a matched one is known as its correspondences (and priors) say.
TEST(Pipeline, TheMappedPoseCovarianceIsZeroWhereTheMapStartsAndUnknownWhereUnmatched) {
  const auto covariance = [](const MappingOutput& mapped) {
    return mapped_pose_covariance(mapped.match, starts_map(mapped), std::nullopt);
  };
  MappingOutput first;
  EXPECT_TRUE(covariance(first).isZero());

  MappingOutput unmatched;
  unmatched.motion = Eigen::Isometry3d::Identity();
  EXPECT_TRUE(covariance(unmatched).isApprox(1e4 * Matrix6d::Identity()));

  MappingOutput localizing = first;  // a saved map's frame: its first scan's pose is a guess
  localizing.localization = LocalizationStatus();
  EXPECT_TRUE(covariance(localizing).isApprox(1e4 * Matrix6d::Identity()));

  MappingOutput matched = unmatched;
  matched.match.matched = true;
  matched.match.information = 1e4 * Matrix6d::Identity();  // 1 cm, 0.6 deg
  EXPECT_TRUE(covariance(matched).isApprox(1e-4 * Matrix6d::Identity()));
}
