// The building blocks of odometry and mapping: the KD-tree and the voxel map against a brute-force
// search, and the registration cost functions' analytic Jacobians against finite differences.

#include <gtest/gtest.h>
#include <pcl/filters/voxel_grid.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/mapping/local_map.h"
#include "adaptive_lego_loam/core/odometry/residuals.h"
#include "adaptive_lego_loam/core/spatial/kdtree.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"
#include "adaptive_lego_loam/core/spatial/voxel_map.h"
#include "core/spatial/random_clouds.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

TEST(VoxelFilter, MatchesPclsVoxelGridAndForgetsTheCloudBefore) {
  // One filter used again, as the stages use theirs: each cloud's output is PCL's for that cloud
  // and leaf alone (PCL accumulates in float, hence the tolerance).
  VoxelFilter filter;
  for (const auto& [seed, leaf] : {std::pair{11u, 0.4}, std::pair{12u, 0.2}, std::pair{13u, 1.2}}) {
    SCOPED_TRACE("leaf " + std::to_string(leaf));
    const CloudPtr cloud = random_cloud(seed == 12u ? 20000 : 5000, seed);
    Cloud expected;
    pcl::VoxelGrid<CloudPoint> grid;
    grid.setLeafSize(leaf, leaf, leaf);
    grid.setInputCloud(cloud);
    grid.filter(expected);
    const std::vector<Eigen::Vector3f> ours = sorted_points(*filter(*cloud, leaf));
    const std::vector<Eigen::Vector3f> pcl_points = sorted_points(expected);
    ASSERT_EQ(ours.size(), pcl_points.size());
    for (std::size_t i = 0; i < ours.size(); ++i)
      ASSERT_LT((ours[i] - pcl_points[i]).norm(), 1e-4f) << i;
  }
}

TEST(VoxelFilter, OfTwoCloudsIsTheFilterOfTheirJoin) {
  // The mapping filters a scan's surfaces and outliers together without copying them into one.
  const CloudPtr surfaces = random_cloud(4000, 14), outliers = random_cloud(500, 15);
  Cloud joined = *surfaces;
  joined += *outliers;
  VoxelFilter filter;
  const CloudPtr expected = filter(joined, 0.4);
  const CloudPtr together = filter(*surfaces, *outliers, 0.4);
  ASSERT_EQ(together->size(), expected->size());
  for (std::size_t i = 0; i < expected->size(); ++i) {
    ASSERT_EQ((*together)[i].getVector3fMap(), (*expected)[i].getVector3fMap()) << i;
    ASSERT_EQ((*together)[i].intensity, (*expected)[i].intensity) << i;
  }
  EXPECT_EQ(filter(*surfaces, *outliers, 0.0)->size(), joined.size());  // no filtering
}

TEST(VoxelKeys, AVoxelIndexIsTheFloorOfTheScaledCoordinate) {
  // Points on a voxel's lower face belong to it, points just below it to the voxel below, on both
  // sides of zero and far from the origin.
  for (const double inverse_leaf : {1.0, 2.5, 5.0, 1.0 / 0.3}) {
    SCOPED_TRACE("inverse leaf " + std::to_string(inverse_leaf));
    for (const float coordinate : {0.f, -0.f, 0.4f, -0.4f, 1.f, -1.f, 2.f, -2.f, 1e-30f, -1e-30f,
                                   -0.2f, 0.2f, 123456.7f, -123456.7f}) {
      EXPECT_EQ(voxel_index(coordinate, inverse_leaf),
                static_cast<int64_t>(std::floor(coordinate * inverse_leaf)))
          << coordinate;
    }
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinates(-500.f, 500.f);
  for (int i = 0; i < 100000; ++i) {
    const float coordinate = coordinates(rng);
    ASSERT_EQ(voxel_index(coordinate, 5.0), static_cast<int64_t>(std::floor(coordinate * 5.0)))
        << coordinate;
  }
  EXPECT_EQ(voxel_index(-0.2f, 5.0), -2);  // -0.2f lies just below -0.2
  EXPECT_EQ(voxel_index(-1.f, 1.0), -1);
  EXPECT_EQ(voxel_index(-0.5f, 1.0), -1);
}
