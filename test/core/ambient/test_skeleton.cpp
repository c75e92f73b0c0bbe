#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <random>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/ambient/skeleton.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "core/ambient/filter_scan.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
using test::Box;
using test::Scene;

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
    if (result.skeleton[cell]) {
      ASSERT_FALSE(result.segmentation.ground[cell]);
    }
  }
  EXPECT_EQ(both, result.skeleton_points);
  EXPECT_EQ(result.skeleton_cloud().size(), static_cast<std::size_t>(both));
  // Both labelings dropped something: the skeleton is smaller than either alone.
  EXPECT_LT(both, result.euclidean.kept_points());
  EXPECT_LT(both, result.skeleton_depth.kept_points());
}

namespace {

// Every occupied cell in one kept cluster, nothing in the skeleton: every point is a fragment.
ClusterLabels one_kept_cluster(const RangeImage& image) {
  ClusterLabels labels;
  labels.label.assign(image.size(), ClusterLabels::kNone);
  int points = 0;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (!image.occupied(cell)) continue;
    labels.label[cell] = 1;
    ++points;
  }
  labels.size = {0, points};
  labels.kept = {0, 1};
  return labels;
}

}  // namespace

TEST(Skeleton, ARailsFragmentsAreSmoothAndLeavesAreNot) {
  const SensorParams sensor = test::even_sensor(64, 1800, -24.9, 2.0);
  const RangeProjector projector(sensor);
  // A guard rail beside the road, seen at grazing incidence over a few hundred columns.
  Scene road;
  road.boxes.push_back({{4.0, 3.0, -1.2}, {40.0, 3.1, -0.8}});
  RangeImage rail;
  projector.project(test::render(sensor, road), rail);
  // A bush: each beam hits a leaf at a random depth within 0.5 m.
  std::mt19937 rng(5);
  Scan bush_scan;
  bush_scan.has_ring = true;
  test::add_scatter(sensor, 20, 40, 880, 940, 10.0, 0.5, rng, bush_scan);
  RangeImage bush;
  projector.project(bush_scan, bush);

  const std::vector<uint8_t> no_skeleton(rail.size(), 0);
  const ClusterLabels rail_labels = one_kept_cluster(rail);
  ASSERT_GT(rail_labels.kept_points(), 300);
  EXPECT_GT(fragment_smoothness(rail, rail_labels, no_skeleton, 0.05), 0.95);
  EXPECT_LT(fragment_smoothness(bush, one_kept_cluster(bush), no_skeleton, 0.05), 0.3);
  // Within a tolerance wider than the leaves' depth every fragment is smooth.
  EXPECT_DOUBLE_EQ(fragment_smoothness(bush, one_kept_cluster(bush), no_skeleton, 2.0), 1.0);
  // Skeleton points are not fragments: with all of them skeleton there is nothing to measure.
  const std::vector<uint8_t> all_skeleton(rail.size(), 1);
  EXPECT_DOUBLE_EQ(fragment_smoothness(rail, rail_labels, all_skeleton, 0.05), 0.0);
}
