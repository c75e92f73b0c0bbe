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

using namespace adaptive_lego_loam;

namespace {

CloudPtr random_cloud(int size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(-10.f, 10.f);
  CloudPtr cloud(new Cloud);
  for (int i = 0; i < size; ++i) {
    CloudPoint p;
    p.x = coordinate(random);
    p.y = coordinate(random);
    p.z = 0.1f * coordinate(random);  // flat, as scans are
    cloud->push_back(p);
  }
  // Duplicates and points on one line: ties and zero extents.
  for (int i = 0; i < 20; ++i)
    cloud->push_back((*cloud)[i]);
  for (int i = 0; i < 30; ++i) {
    CloudPoint p;
    p.x = 0.5f * static_cast<float>(i);
    p.y = p.z = 1.f;
    cloud->push_back(p);
  }
  return cloud;
}

// Squared distances of the k nearest points within the bound, nearest first.
std::vector<float> brute_force(const Cloud& cloud, const Eigen::Vector3f& query, int k,
                               float max_squared) {
  std::vector<float> squared;
  for (const CloudPoint& p : cloud) {
    const float dx = p.x - query.x(), dy = p.y - query.y(), dz = p.z - query.z();
    const float d = dx * dx + dy * dy + dz * dz;  // as the tree sums them
    if (d <= max_squared) squared.push_back(d);
  }
  std::sort(squared.begin(), squared.end());
  squared.resize(std::min<std::size_t>(squared.size(), k));
  return squared;
}

}  // namespace

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
