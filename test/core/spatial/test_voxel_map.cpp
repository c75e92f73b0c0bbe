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

namespace {

// The voxel map's k nearest against a brute-force search over the voxel filter of
// `expected_points`.
void expect_nearest_match_brute_force(const VoxelMap& map, const Cloud& expected_points,
                                      double leaf, unsigned seed) {
  const CloudPtr centroids = voxel_filter(expected_points, leaf);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(-11.f, 11.f);
  for (int query_index = 0; query_index < 300; ++query_index) {
    const Eigen::Vector3f query(coordinate(random), coordinate(random), 0.1f * coordinate(random));
    for (int k : {1, 6, 20}) {
      for (float bound : {1.21f, 0.3f}) {
        Eigen::Vector3f points[20];
        float squared[20];
        const int found = map.nearest(query, k, points, squared, bound);
        const std::vector<float> expected = brute_force(*centroids, query, k, bound);
        ASSERT_EQ(found, static_cast<int>(expected.size())) << "k " << k << " bound " << bound;
        for (int i = 0; i < found; ++i) {
          EXPECT_NEAR(squared[i], expected[i], 1e-5f);
          EXPECT_NEAR((points[i] - query).squaredNorm(), squared[i], 1e-4f);
        }
      }
    }
  }
}

}  // namespace

TEST(VoxelMap, HoldsTheVoxelFilterAndFindsItsNearestCentroids) {
  const CloudPtr cloud = random_cloud(20000, 3);
  VoxelMap map(0.4, 1.1);
  map.add(*cloud);
  const std::vector<Eigen::Vector3f> centroids = sorted_points(map.centroids());
  const std::vector<Eigen::Vector3f> filtered = sorted_points(*voxel_filter(*cloud, 0.4));
  ASSERT_EQ(centroids.size(), filtered.size());
  EXPECT_EQ(map.size(), filtered.size());
  for (std::size_t i = 0; i < filtered.size(); ++i)
    EXPECT_LT((centroids[i] - filtered[i]).norm(), 1e-5f);
  expect_nearest_match_brute_force(map, *cloud, 0.4, 5);
}

TEST(VoxelMap, RemovedPointsLeaveTheRestAsIfAddedAlone) {
  const CloudPtr first = random_cloud(15000, 21), second = random_cloud(15000, 22);
  VoxelMap map(0.2, 1.1);  // cells of 6 x 6 x 6 voxels
  map.add(*first);
  map.add(*second);
  map.remove(*first);
  expect_nearest_match_brute_force(map, *second, 0.2, 9);
  map.remove(*second);
  EXPECT_TRUE(map.empty());
  Eigen::Vector3f point;
  float squared;
  EXPECT_EQ(map.nearest(Eigen::Vector3f::Zero(), 1, &point, &squared, 1.f), 0);
}

TEST(VoxelMap, CellsEmptiedAndReusedAnswerAsIfNew) {
  // Sparse clouds: about 5 points a cell, so removing one empties many cells and the next one
  // takes their freed places (and table entries) again.
  const CloudPtr a = random_cloud(3000, 31), b = random_cloud(3000, 32), c = random_cloud(3000, 33);
  VoxelMap map(0.2, 1.1);
  map.add(*a);
  map.add(*b);
  map.remove(*a);
  map.add(*c);
  Cloud b_and_c = *b;
  b_and_c += *c;
  expect_nearest_match_brute_force(map, b_and_c, 0.2, 10);
  map.remove(*b);
  expect_nearest_match_brute_force(map, *c, 0.2, 11);
}

TEST(VoxelMap, SearchesNoFurtherThanItsRadius) {
  Cloud cloud;
  CloudPoint p;
  p.x = 1.5f;
  p.y = p.z = 0.f;
  cloud.push_back(p);
  VoxelMap map(0.5, 1.0);
  map.add(cloud);
  Eigen::Vector3f point;
  float squared;
  EXPECT_EQ(map.nearest(Eigen::Vector3f::Zero(), 1, &point, &squared, 100.f), 0);
  EXPECT_EQ(map.nearest(Eigen::Vector3f(0.6f, 0.f, 0.f), 1, &point, &squared, 100.f), 1);
  EXPECT_NEAR(squared, 0.81f, 1e-5f);
}
