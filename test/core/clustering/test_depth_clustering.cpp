#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <map>
#include <random>

#include "adaptive_lego_loam/core/clustering/depth_clustering.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using adaptive_lego_loam::test::Box;
using adaptive_lego_loam::test::Scene;

namespace {

// HDL-64E-like layout, evenly spaced: 64 rows over [-24.9, 2] deg, 1800 columns.
SensorParams sensor64() {
  return test::even_sensor(64, 1800, -24.9, 2.0);
}

struct Clustered {
  RangeImage image;
  ClusterLabels labels;
};

Clustered cluster_scan(const SensorParams& sensor, const Scan& scan, double beta0_deg,
                       ClusterSizeRule rule = {}) {
  Clustered out;
  RangeProjector projector(sensor);
  projector.project(scan, out.image);
  DepthClustering clustering(projector.geometry());
  clustering.cluster(out.image, {}, beta0_deg, rule, out.labels);
  return out;
}

// Cluster ids of the occupied cells, with the number of cells in each.
std::map<int, int> ids_of(const Clustered& c) {
  std::map<int, int> ids;
  for (int cell = 0; cell < c.image.size(); ++cell) {
    if (c.image.occupied(cell)) ++ids[c.labels.label[cell]];
  }
  return ids;
}

double reference_beta(double d1, double d2, double alpha) {
  return std::atan2(d2 * std::sin(alpha), d1 - d2 * std::cos(alpha));
}

}  // namespace

TEST(DepthCriterion, TrigFreeFormMatchesTheAngleDefinition) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> range(0.5, 80.0), alpha(0.001, 0.05), beta0(0.05, 1.5);
  for (int i = 0; i < 200000; ++i) {
    const double a = range(rng), b = range(rng), step = alpha(rng), threshold = beta0(rng);
    const double beta = reference_beta(std::max(a, b), std::min(a, b), step);
    if (std::fabs(beta - threshold) < 1e-6) continue;  // too close to call in float
    ASSERT_EQ(depth_points_join(float(a), float(b), std::sin(step), std::cos(step),
                                std::sin(threshold), std::cos(threshold)),
              beta > threshold)
        << a << " " << b << " " << step << " " << threshold;
  }
}

TEST(DepthCriterion, HandPickedAngles) {
  const double alpha = 0.2 * M_PI / 180.0;
  // Equal ranges: beta = 90 - alpha/2 deg, joins at any beta0 below that.
  EXPECT_TRUE(depth_points_join(10.f, 10.f, std::sin(alpha), std::cos(alpha), std::sin(1.0),
                                std::cos(1.0)));
  // 10 m against 12 m one column apart: beta is about 0.6 deg, splits even at 1 deg.
  const double one_deg = M_PI / 180.0;
  EXPECT_FALSE(depth_points_join(10.f, 12.f, std::sin(alpha), std::cos(alpha), std::sin(one_deg),
                                 std::cos(one_deg)));
}

TEST(DepthClustering, FlatWallIsOneClusterAtAnyBeta0) {
  const SensorParams sensor = sensor64();
  Scene scene;
  scene.boxes.push_back({{10.0, -4.0, -1.5}, {10.2, 4.0, 1.5}});
  const Scan scan = test::render(sensor, scene);
  ASSERT_GT(scan.points.size(), 2000u);
  for (double beta0 = 10.0; beta0 <= 60.0; beta0 += 10.0) {
    SCOPED_TRACE("beta0 " + std::to_string(beta0));
    const Clustered c = cluster_scan(sensor, scan, beta0);
    const auto ids = ids_of(c);
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_NE(ids.begin()->first, ClusterLabels::kNone);
    EXPECT_EQ(c.labels.kept_points(), static_cast<int>(scan.points.size()));
  }
}

TEST(DepthClustering, BoxBehindBoxSplitsAt60) {
  const SensorParams sensor = sensor64();
  Scene scene;
  scene.boxes.push_back({{8.0, -1.0, -1.5}, {9.0, 1.0, 0.5}});   // front box
  scene.boxes.push_back({{12.0, 0.0, -1.5}, {13.0, 3.0, 1.0}});  // behind it, sticking out
  const Scan scan = test::render(sensor, scene);
  const Clustered c = cluster_scan(sensor, scan, 60.0);
  std::map<int, int> front_ids, back_ids;
  for (int cell = 0; cell < c.image.size(); ++cell) {
    if (!c.image.occupied(cell)) continue;
    const float x = c.image.point(cell).x;
    ++(x < 10.f ? front_ids : back_ids)[c.labels.label[cell]];
  }
  ASSERT_EQ(front_ids.size(), 1u);
  ASSERT_EQ(back_ids.size(), 1u);
  EXPECT_NE(front_ids.begin()->first, back_ids.begin()->first);
  EXPECT_EQ(c.labels.kept_clusters(), 2);
}

TEST(DepthClustering, LeafScatterDroppedAt60KeptAt10) {
  const SensorParams sensor = sensor64();
  // A bush: each beam through it hits a leaf at a random depth within 0.5 m.
  std::mt19937 rng(11);
  Scan scan;
  scan.has_ring = true;
  test::add_scatter(sensor, 20, 40, 880, 940, 10.0, 0.5, rng, scan);
  const int leaves = static_cast<int>(scan.points.size());
  const int kept_at_60 = cluster_scan(sensor, scan, 60.0).labels.kept_points();
  const int kept_at_10 = cluster_scan(sensor, scan, 10.0).labels.kept_points();
  EXPECT_LT(kept_at_60, 0.1 * leaves) << "kept " << kept_at_60 << " of " << leaves;
  EXPECT_GT(kept_at_10, 0.8 * leaves) << "kept " << kept_at_10 << " of " << leaves;
}

TEST(DepthClustering, ClusterAcrossColumnZeroIsJoined) {
  const SensorParams sensor = sensor64();
  Scene scene;
  scene.boxes.push_back({{-10.2, -2.0, -1.5}, {-10.0, 2.0, 1.0}});  // straddles azimuth +-pi
  const Scan scan = test::render(sensor, scene);
  const Clustered c = cluster_scan(sensor, scan, 60.0);
  bool at_first_col = false, at_last_col = false;
  for (int row = 0; row < c.image.rows(); ++row) {
    at_first_col |= c.image.occupied(c.image.cell(row, 0));
    at_last_col |= c.image.occupied(c.image.cell(row, c.image.cols() - 1));
  }
  ASSERT_TRUE(at_first_col && at_last_col) << "the object must cross column 0";
  EXPECT_EQ(ids_of(c).size(), 1u);
}

TEST(DepthClustering, SizeRuleKeepsTallThinClustersAndDropsSpecks) {
  const SensorParams sensor = sensor64();
  Scan scan;
  scan.has_ring = true;
  // A pole: 6 points in one column over 6 rows (>= 5 points over >= 3 rows: kept).
  for (int row = 30; row < 36; ++row)
    scan.points.push_back(test::cell_point(sensor, row, 100, 7.0));
  // A speck: 4 points in a 2 x 2 block (dropped).
  for (int row = 30; row < 32; ++row) {
    for (int col = 500; col < 502; ++col)
      scan.points.push_back(test::cell_point(sensor, row, col, 7.0));
  }
  const Clustered c = cluster_scan(sensor, scan, 60.0);
  EXPECT_EQ(c.labels.clusters(), 2);
  EXPECT_EQ(c.labels.kept_clusters(), 1);
  EXPECT_EQ(c.labels.kept_points(), 6);
}

TEST(DepthClustering, ExcludedCellsTakeNoPart) {
  const SensorParams sensor = sensor64();
  Scene scene;
  scene.boxes.push_back({{10.0, -4.0, -1.5}, {10.2, 4.0, 1.5}});
  const Scan scan = test::render(sensor, scene);
  RangeProjector projector(sensor);
  RangeImage image;
  projector.project(scan, image);
  std::vector<uint8_t> excluded(image.size(), 1);
  ClusterLabels labels;
  DepthClustering(projector.geometry()).cluster(image, excluded, 60.0, {}, labels);
  EXPECT_EQ(labels.clusters(), 0);
}

TEST(DepthClustering, ReclusterMatchesClusteringAfresh) {
  const SensorParams sensor = sensor64();
  std::mt19937 rng(5);
  Scan scan;
  scan.has_ring = true;
  test::add_scatter(sensor, 20, 40, 880, 940, 10.0, 0.5, rng, scan);  // a bush
  test::add_scatter(sensor, 10, 50, -12, 12, 15.0, 0.5, rng, scan);  // a rough wall across column 0
  RangeProjector projector(sensor);
  RangeImage image;
  projector.project(scan, image);
  std::vector<uint8_t> excluded(image.size(), 0);
  for (int cell = 0; cell < image.cell(25, 0); ++cell)
    excluded[cell] = 1;

  DepthClustering reused(projector.geometry()), fresh(projector.geometry());
  ClusterLabels again, expected;
  reused.cluster(image, excluded, 60.0, {30, INT_MAX, INT_MAX}, again);
  for (const double beta0 : {45.0, 10.0, 10.0, 80.0, 20.0}) {
    reused.recluster(image, beta0, {}, again);
    fresh.cluster(image, excluded, beta0, {}, expected);
    EXPECT_EQ(again.label, expected.label) << "beta0 " << beta0;
    EXPECT_EQ(again.size, expected.size) << "beta0 " << beta0;
    EXPECT_EQ(again.kept, expected.kept) << "beta0 " << beta0;
  }
}
