#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/ambient/skeleton.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "support/scenes.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
using test::Box;
using test::Scene;

namespace {

std::map<int, int> cluster_sizes_of(const ClusterLabels& labels, const RangeImage& image,
                                    const std::function<bool(const ScanPoint&)>& select) {
  std::map<int, int> sizes;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (image.occupied(cell) && select(image.point(cell))) ++sizes[labels.label[cell]];
  }
  return sizes;
}

}  // namespace

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

// Within one row, neighbours k columns apart at ranges r and r + dr are |AB| = sqrt((k a r)^2 +
// dr^2) apart (a the column step), so the distance test |AB| < gamma sin(k a) r joins them only
// while dr < sqrt(gamma^2 - 1) k a r (0.66 k a r at gamma 1.2), where the range-difference test
// allows dr < gamma k a r: on a wall turned 42-48 deg from the beam (dr = tan(incidence) k a r,
// 0.90-1.11 k a r) the first cuts every column apart and the second keeps the wall whole. A low
// wall seen by one row only, so that no neighbour in another row bridges the columns.
TEST(EuclideanClustering, RangeDifferenceCriterionKeepsAnObliqueWallThatTheDistanceTestCuts) {
  const SensorParams sensor = test::even_sensor(3, 1800, -15.0, 15.0);
  Scene scene;
  scene.boxes = {{{0.0, 4.0, -0.3}, {40.0, 4.3, 0.3}}};
  const Scan scan = test::render(sensor, scene);
  RangeProjector projector(sensor);
  RangeImage image;
  projector.project(scan, image);
  auto oblique = [](const ScanPoint& p) {
    const double azimuth_deg = std::atan2(p.y, p.x) * 180.0 / M_PI;
    return p.y < 4.01 && azimuth_deg > 42.0 && azimuth_deg < 48.0;
  };
  ClusterLabels labels;
  EuclideanClusteringParams distance;
  EuclideanClustering(projector.geometry(), distance).cluster(image, {}, labels);
  const auto by_distance = cluster_sizes_of(labels, image, oblique);
  EuclideanClusteringParams range_difference;
  range_difference.criterion = EuclideanCriterion::kRangeDifference;
  EuclideanClustering(projector.geometry(), range_difference).cluster(image, {}, labels);
  const auto by_range = cluster_sizes_of(labels, image, oblique);
  EXPECT_GT(by_distance.size(), 10u);
  EXPECT_EQ(by_range.size(), 1u);
  // gamma * alpha * r_A for the range-difference test.
  EuclideanClustering clustering(projector.geometry(), range_difference);
  const double column_step = 2 * M_PI / sensor.columns;
  EXPECT_NEAR(clustering.threshold(1, 0, 3, 10.0), 1.2 * 3 * column_step * 10.0, 1e-9);
}
