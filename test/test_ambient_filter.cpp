#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "adaptive_lego_loam/core/ambient_filter.h"
#include "adaptive_lego_loam/core/degeneration_kdtree.h"
#include "adaptive_lego_loam/core/euclidean_clustering.h"
#include "adaptive_lego_loam/core/skeleton.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "synthetic.h"

using namespace adaptive_lego_loam;
using test::Box;
using test::Scene;

namespace {

// HDL-64E-like layout, evenly spaced, ground possible in rows up to -3.5 deg.
Config synthetic_config() {
  Config config;
  config.sensor = test::even_sensor(64, 1800, -24.9, 2.0);
  config.sensor.ground_rows = 50;
  config.sensor.max_range = 100.0;
  return config;
}

Scene with_ground(std::vector<Box> boxes) {
  Scene scene;
  scene.has_ground = true;
  scene.ground_z = -1.73;
  scene.boxes = std::move(boxes);
  return scene;
}

Scene corridor() {
  return with_ground({{{-60, 2.8, -1.73}, {60, 3.0, 3.0}}, {{-60, -3.0, -1.73}, {60, -2.8, 3.0}}});
}

// A square room, 12 m a side.
Scene box_room() {
  return with_ground({{{5.8, -6, -1.73}, {6.0, 6, 3}},
                      {{-6.0, -6, -1.73}, {-5.8, 6, 3}},
                      {{-6, 5.8, -1.73}, {6, 6.0, 3}},
                      {{-6, -6.0, -1.73}, {6, -5.8, 3}}});
}

// Four blocks of buildings at the corners of two crossing 8 m wide streets.
Scene crossroads() {
  std::vector<Box> blocks;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      const Eigen::Vector3d a(sx * 4, sy * 4, -1.73), b(sx * 40, sy * 40, 8.0);
      blocks.push_back({a.cwiseMin(b), a.cwiseMax(b)});
    }
  }
  return with_ground(blocks);
}

AmbientFilterResult filter(const Config& config, const Scan& scan) {
  AmbientFilter ambient(config);
  AmbientFilterResult result;
  ambient.process(scan, result);
  return result;
}

std::map<int, int> cluster_sizes_of(const ClusterLabels& labels, const RangeImage& image,
                                    const std::function<bool(const ScanPoint&)>& select) {
  std::map<int, int> sizes;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (image.occupied(cell) && select(image.point(cell))) ++sizes[labels.label[cell]];
  }
  return sizes;
}

}  // namespace

TEST(Degeneration, CorridorIsDegenerateAlongItsAxis) {
  const Config config = synthetic_config();
  const AmbientFilterResult result = filter(config, test::render(config.sensor, corridor()));
  ASSERT_TRUE(result.degeneration.valid);
  EXPECT_GT(result.skeleton_points, 1000);
  EXPECT_GT(result.degeneration.normals, 100);
  EXPECT_GE(result.mu, 0.8);
  EXPECT_GE(std::fabs(result.degeneration.weak_direction.x()), std::cos(10.0 * M_PI / 180.0))
      << result.degeneration.weak_direction.transpose();
  // A degenerate scene gets the lenient end of the threshold range.
  EXPECT_LT(result.beta0_deg, 20.0);
}

TEST(Degeneration, BoxRoomAndCrossroadsAreWellConstrained) {
  const Config config = synthetic_config();
  for (const auto& [name, scene] :
       {std::pair<const char*, Scene>{"box room", box_room()}, {"crossroads", crossroads()}}) {
    SCOPED_TRACE(name);
    const AmbientFilterResult result = filter(config, test::render(config.sensor, scene));
    ASSERT_TRUE(result.degeneration.valid);
    EXPECT_GT(result.degeneration.normals, 100);
    EXPECT_LE(result.mu, 0.3);
    EXPECT_GT(result.beta0_deg, 45.0);
  }
}

TEST(Degeneration, HandMadeNormals) {
  auto normal = [](float x, float y, float z, float weight) {
    NormalFeature n;
    n.normal = Eigen::Vector3f(x, y, z).normalized();
    n.weight = weight;
    return n;
  };
  // All normals along +-y: k infinite, mu = 1, weak direction x.
  Degeneration d = degeneration_from_normals({normal(0, 1, 0, 2), normal(0, -1, 0, 1)});
  EXPECT_TRUE(d.valid);
  EXPECT_DOUBLE_EQ(d.mu, 1.0);
  EXPECT_NEAR(std::fabs(d.weak_direction.x()), 1.0, 1e-12);
  // Equal weight along x and y: k = 1, mu = 0.
  d = degeneration_from_normals({normal(1, 0, 0, 1), normal(0, 1, 0, 1)});
  EXPECT_NEAR(d.mu, 0.0, 1e-12);
  // Three along y, one along x (equal weights): k = 3, mu = 2/3.
  d = degeneration_from_normals(
      {normal(0, 1, 0, 1), normal(0, -1, 0, 1), normal(0, 1, 0, 1), normal(1, 0, 0, 1)});
  EXPECT_NEAR(d.mu, 2.0 / 3.0, 1e-12);
  // Only vertical normals (a flat ceiling): nothing horizontal, mu unknown.
  EXPECT_FALSE(degeneration_from_normals({normal(0, 0, 1, 1)}).valid);
  EXPECT_FALSE(degeneration_from_normals({}).valid);
  EXPECT_DOUBLE_EQ(beta0_from_mu(1.0, 10, 60), 10.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.0, 10, 60), 60.0);
  EXPECT_DOUBLE_EQ(beta0_from_mu(0.5, 10, 60), 35.0);
}

TEST(EuclideanClustering, ThresholdGrowsWithRange) {
  const Config config = synthetic_config();
  // Two boxes 0.5 m apart at 5 m ahead, and a wall 20 m wide seen from 40 m behind.
  Scene scene;
  scene.boxes = {{{5.0, -1.2, -1.0}, {5.5, -0.25, 1.0}},
                 {{5.0, 0.25, -1.0}, {5.5, 1.2, 1.0}},
                 {{-40.5, -10.0, -2.0}, {-40.0, 10.0, 3.0}}};
  const Scan scan = test::render(config.sensor, scene);
  RangeProjector projector(config.sensor);
  RangeImage image;
  projector.project(scan, image);

  EuclideanClusteringParams adaptive;
  ClusterLabels labels;
  EuclideanClustering(projector.geometry(), adaptive).cluster(image, {}, labels);
  // The boxes' front faces (their inner sides, seen edge-on, are other clusters).
  auto near_left = [](const ScanPoint& p) { return p.x > 0 && p.x < 5.01 && p.y < 0; };
  auto near_right = [](const ScanPoint& p) { return p.x > 0 && p.x < 5.01 && p.y > 0; };
  auto far_wall = [](const ScanPoint& p) { return p.x < -30; };
  const auto left = cluster_sizes_of(labels, image, near_left);
  const auto right = cluster_sizes_of(labels, image, near_right);
  const auto wall = cluster_sizes_of(labels, image, far_wall);
  ASSERT_EQ(left.size(), 1u);
  ASSERT_EQ(right.size(), 1u);
  EXPECT_NE(left.begin()->first, right.begin()->first);
  EXPECT_EQ(wall.size(), 1u) << "the far wall must stay one cluster";

  // A fixed 0.1 m threshold keeps the near boxes apart but shatters the far wall.
  EuclideanClusteringParams fixed;
  fixed.fixed_threshold = 0.1;
  EuclideanClustering(projector.geometry(), fixed).cluster(image, {}, labels);
  EXPECT_GT(cluster_sizes_of(labels, image, far_wall).size(), 10u);
  EXPECT_EQ(cluster_sizes_of(labels, image, near_left).size(), 1u);

  // The adaptive threshold is gamma * sin(alpha) * |OB|.
  EuclideanClustering clustering(projector.geometry(), adaptive);
  const double column_step = 2 * M_PI / 1800;
  EXPECT_NEAR(clustering.threshold(10, 0, 2, 40.0), 1.2 * std::sin(2 * column_step) * 40.0, 1e-9);
}

TEST(Skeleton, IsExactlyTheIntersectionOnARealScan) {
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
  const Scan scan =
      read_kitti_bin(std::string(TEST_DATA_DIR) + "/kitti_seq07/velodyne/0000000000.bin");
  const AmbientFilterResult result = filter(config, scan);
  ASSERT_GT(result.skeleton_points, 1000);
  int both = 0;
  for (std::size_t cell = 0; cell < result.skeleton.size(); ++cell) {
    const bool kept_by_both =
        result.euclidean.point_kept(cell) && result.skeleton_depth.point_kept(cell);
    ASSERT_EQ(result.skeleton[cell] != 0, kept_by_both) << "cell " << cell;
    both += kept_by_both;
    if (result.skeleton[cell]) ASSERT_FALSE(result.segmentation.ground[cell]);
  }
  EXPECT_EQ(both, result.skeleton_points);
  EXPECT_EQ(result.skeleton_cloud().size(), static_cast<std::size_t>(both));
  // Both labelings dropped something: the skeleton is smaller than either alone.
  EXPECT_LT(both, result.euclidean.kept_points());
  EXPECT_LT(both, result.skeleton_depth.kept_points());
}

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

TEST(KdTreeBaseline, AgreesOnTheCorridor) {
  const Config config = synthetic_config();
  const AmbientFilterResult result = filter(config, test::render(config.sensor, corridor()));
  std::vector<NormalFeature> normals;
  KdTreeNormalParams params;
  params.max_range = config.sensor.max_range;
  // Every 10th point keeps the test fast (the near walls are dense); the baseline proper uses all.
  const auto all_points = non_ground_points(result.segmentation);
  std::vector<ScanPoint> points;
  for (std::size_t i = 0; i < all_points.size(); i += 10)
    points.push_back(all_points[i]);
  kdtree_normals(points, params, normals);
  EXPECT_GT(normals.size(), result.normals.size());
  const Degeneration d = degeneration_from_normals(normals);
  ASSERT_TRUE(d.valid);
  EXPECT_GE(d.mu, 0.8);
}
