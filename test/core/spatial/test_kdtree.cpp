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

TEST(KdTree, MatchesBruteForce) {
  const CloudPtr cloud = random_cloud(3000, 7);
  PointKdTree tree;
  tree.build(cloud);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> coordinate(-12.f, 12.f);
  for (int query_index = 0; query_index < 300; ++query_index) {
    const Eigen::Vector3f query(coordinate(random), coordinate(random), 0.1f * coordinate(random));
    for (int k : {1, 5, 15}) {
      for (float bound : {std::numeric_limits<float>::infinity(), 1.0f, 0.05f}) {
        uint32_t indices[15];
        float squared[15];
        const int found = tree.nearest(query, k, indices, squared, bound);
        const std::vector<float> expected = brute_force(*cloud, query, k, bound);
        ASSERT_EQ(found, static_cast<int>(expected.size())) << "k " << k << " bound " << bound;
        for (int i = 0; i < found; ++i) {
          EXPECT_NEAR(squared[i], expected[i], 1e-5f * expected[i]);
          EXPECT_NEAR(((*cloud)[indices[i]].getVector3fMap() - query).squaredNorm(), squared[i],
                      1e-4f);
        }
      }
    }
  }
}

TEST(KdTree, EmptyAndTinyClouds) {
  PointKdTree tree;
  uint32_t index;
  float squared;
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(tree.nearest(Eigen::Vector3f::Zero(), 1, &index, &squared), 0);
  tree.build(CloudPtr(new Cloud));
  EXPECT_TRUE(tree.empty());
  CloudPtr one(new Cloud);
  CloudPoint p;
  p.x = 1.f;
  p.y = p.z = 0.f;
  one->push_back(p);
  tree.build(one);
  uint32_t indices[3];
  float distances[3];
  EXPECT_EQ(tree.nearest(Eigen::Vector3f::Zero(), 3, indices, distances), 1);
  EXPECT_EQ(indices[0], 0u);
  EXPECT_FLOAT_EQ(distances[0], 1.f);
  // The bound is inclusive.
  EXPECT_EQ(tree.nearest(Eigen::Vector3f::Zero(), 3, indices, distances, 1.f), 1);
  EXPECT_EQ(tree.nearest(Eigen::Vector3f::Zero(), 3, indices, distances, 0.99f), 0);
}
