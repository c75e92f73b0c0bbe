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
