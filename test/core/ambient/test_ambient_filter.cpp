#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/ambient/skeleton.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "core/ambient/filter_scan.h"
#include "support/scenes.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
using test::Box;
using test::Scene;

TEST(AmbientFilter, SameInputGivesBitIdenticalMu) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  const Scan scan =
      read_kitti_bin(std::string(TEST_DATA_DIR) + "/kitti_seq07/velodyne/0000000001.bin");
  AmbientFilter first(config), second(config);
  AmbientFilterResult a, b, c;
  first.process(scan, a);
  second.process(scan, b);
  first.reset();
  first.process(scan, c);
  ASSERT_TRUE(a.degeneration.valid);
  EXPECT_EQ(std::memcmp(&a.mu, &b.mu, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&a.mu, &c.mu, sizeof(double)), 0);
  EXPECT_EQ(a.degeneration.normals, b.degeneration.normals);
  EXPECT_EQ(a.segmentation.cloud.points.size(), b.segmentation.cloud.points.size());
  EXPECT_EQ(a.beta0_deg, b.beta0_deg);
}

// The skeleton (and so mu) comes from its own strict threshold; beta0's range only maps mu.
TEST(AmbientFilter, TheSkeletonKeepsItsThresholdWhateverBeta0sRange) {
  const Config kitti = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  const Scan scan =
      read_kitti_bin(std::string(TEST_DATA_DIR) + "/kitti_seq07/velodyne/0000000001.bin");
  auto filtered = [&](double beta0_max_deg, double skeleton_beta0_deg) {
    Config config = kitti;
    config.ambient.beta0_min_deg = 10.0;
    config.ambient.beta0_max_deg = beta0_max_deg;
    config.ambient.mu_strict_below = 0.0;  // the paper's linear map
    config.ambient.mu_lenient_above = 1.0;
    config.ambient.skeleton_beta0_deg = skeleton_beta0_deg;
    AmbientFilterResult result;
    AmbientFilter(config).process(scan, result);
    return result;
  };
  const AmbientFilterResult paper = filtered(60.0, 60.0);
  const AmbientFilterResult narrow = filtered(20.0, 60.0);
  ASSERT_TRUE(paper.degeneration.valid);
  EXPECT_EQ(narrow.skeleton_points, paper.skeleton_points);
  EXPECT_DOUBLE_EQ(narrow.mu, paper.mu);
  EXPECT_DOUBLE_EQ(narrow.beta0_deg, paper.mu * (10.0 - 20.0) + 20.0);
  EXPECT_LT(narrow.beta0_deg, paper.beta0_deg);
  // A lenient threshold for the skeleton joins more pairs into large clusters.
  EXPECT_GT(filtered(20.0, 20.0).skeleton_points, paper.skeleton_points);
}

TEST(AmbientFilter, ScanWithoutSkeletonKeepsPreviousBeta0) {
  const Config config = synthetic_config();
  AmbientFilter ambient(config);
  AmbientFilterResult result;

  Scan empty;
  empty.has_ring = true;  // the synthetic sensor takes rows from the ring field
  // Before any mu is known, an empty scan gets the strict default and no crash.
  ambient.process(empty, result);
  EXPECT_FALSE(result.degeneration.valid);
  EXPECT_EQ(result.skeleton_points, 0);
  EXPECT_DOUBLE_EQ(result.beta0_deg, config.ambient.beta0_max_deg);

  ambient.process(test::render(config.sensor, corridor()), result);
  ASSERT_TRUE(result.degeneration.valid);
  const double corridor_beta0 = result.beta0_deg;
  const double corridor_mu = result.mu;

  // Only ground (the beams of the ground rows): no skeleton, mu unknown, the previous threshold
  // stays.
  Scan ground_only = test::render(config.sensor, with_ground({}));
  ground_only.points.erase(
      std::remove_if(ground_only.points.begin(), ground_only.points.end(),
                     [&](const ScanPoint& p) { return p.ring > config.sensor.ground_rows; }),
      ground_only.points.end());
  ambient.process(ground_only, result);
  EXPECT_FALSE(result.degeneration.valid);
  EXPECT_EQ(result.skeleton_points, 0);
  EXPECT_DOUBLE_EQ(result.beta0_deg, corridor_beta0);
  EXPECT_DOUBLE_EQ(result.mu, corridor_mu);
  EXPECT_GT(result.segmentation.cloud.points.size(), 0u) << "ground still feeds the odometry";

  ambient.process(empty, result);
  EXPECT_DOUBLE_EQ(result.beta0_deg, corridor_beta0);
}

TEST(AmbientFilter, FixedModeIsLeGoLoamWithThatBeta0) {
  const Config kitti = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  const Scan scan =
      read_kitti_bin(std::string(TEST_DATA_DIR) + "/kitti_seq07/velodyne/0000000002.bin");
  for (double beta0 : {10.0, 30.0, 60.0}) {
    Config config = kitti;
    config.ambient.mode = Beta0Mode::kFixed;
    config.ambient.fixed_beta0_deg = beta0;
    const AmbientFilterResult fixed = filter(config, scan);
    Segmenter segmenter(kitti.sensor, kitti.segmentation);
    SegmentationResult lego;
    segmenter.project_and_mark_ground(scan, lego);
    segmenter.cluster_and_build(scan, beta0, lego);
    EXPECT_EQ(fixed.beta0_deg, beta0);
    EXPECT_FALSE(fixed.adaptive);
    ASSERT_EQ(fixed.segmentation.cloud.points.size(), lego.cloud.points.size());
    EXPECT_EQ(fixed.segmentation.clusters.label, lego.clusters.label);
  }
}

TEST(AmbientFilter, LargerBeta0RemovesMoreOnRealScan) {
  // The premise of the method on real data: 60 deg keeps fewer points than 10 deg.
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  const Scan scan =
      read_kitti_bin(std::string(TEST_DATA_DIR) + "/kitti_seq07/velodyne/0000000000.bin");
  Segmenter segmenter(config.sensor, config.segmentation);
  SegmentationResult result;
  segmenter.project_and_mark_ground(scan, result);
  segmenter.cluster_and_build(scan, 10.0, result);
  const int kept_at_10 = result.clusters.kept_points();
  segmenter.cluster_and_build(scan, 60.0, result);
  EXPECT_LT(result.clusters.kept_points(), 0.9 * kept_at_10);
}

// From ambient_filter.mu_keep_every_cluster on, the adaptive filter keeps what no segmentation
// keeps; below it, the sensor's size rule drops small clusters as before.
TEST(AmbientFilter, FromTheKeepMuOnEveryClusterStays) {
  const Config vlp16 = load_config(std::string(CONFIG_DIR) + "/vlp16.yaml");
  const Scan scan = read_pcd(std::string(TEST_DATA_DIR) + "/vlp16/vlp16_indoor.pcd");
  auto kept = [&](Beta0Mode mode, double keep_mu) {
    Config config = vlp16;
    config.ambient.mode = mode;
    config.ambient.mu_keep_every_cluster = keep_mu;
    return filter(config, scan);
  };
  const AmbientFilterResult never = kept(Beta0Mode::kAdaptive, 2.0);
  ASSERT_TRUE(never.degeneration.valid);
  const int none_points = kept(Beta0Mode::kNone, 2.0).segmentation.clusters.kept_points();
  const AmbientFilterResult at_mu = kept(Beta0Mode::kAdaptive, never.mu);
  const AmbientFilterResult above_mu = kept(Beta0Mode::kAdaptive, never.mu + 0.01);
  EXPECT_LT(never.segmentation.clusters.kept_points(), none_points);
  EXPECT_EQ(at_mu.segmentation.clusters.kept_points(), none_points);
  EXPECT_TRUE(at_mu.every_cluster_kept);
  EXPECT_FALSE(never.every_cluster_kept);
  EXPECT_FALSE(above_mu.every_cluster_kept);
  EXPECT_DOUBLE_EQ(at_mu.beta0_deg, never.beta0_deg);
  EXPECT_EQ(above_mu.segmentation.clusters.kept_points(),
            never.segmentation.clusters.kept_points());
}
