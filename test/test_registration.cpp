// The building blocks of odometry and mapping: the KD-tree and the voxel map against a brute-force
// search, and the registration cost functions' analytic Jacobians against finite differences.

#include <gtest/gtest.h>
#include <pcl/filters/voxel_grid.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/kdtree.h"
#include "adaptive_lego_loam/core/mapping.h"
#include "adaptive_lego_loam/core/residuals.h"
#include "adaptive_lego_loam/core/voxel_filter.h"
#include "adaptive_lego_loam/core/voxel_map.h"

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

namespace {

Correspondences some_matches() {
  Correspondences matches;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  auto vector = [&] {
    return Eigen::Vector3d(coordinate(random), coordinate(random), coordinate(random));
  };
  for (int i = 0; i < 6; ++i) {
    // Near and far from the line or plane: inside and beyond the Huber threshold.
    matches.lines.push_back({vector(), vector(), vector().normalized()});
    const Eigen::Vector3d normal = vector().normalized();
    matches.planes.push_back({vector(), normal, 0.1 * coordinate(random)});
  }
  return matches;
}

// Central differences of `cost` in each entry of each parameter block.
void expect_jacobians_match(const ceres::CostFunction& cost, std::vector<double*> blocks) {
  const int residuals = cost.num_residuals();
  const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
  std::vector<std::vector<double>> jacobians(blocks.size());
  std::vector<double*> jacobian_pointers;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    jacobians[b].resize(residuals * sizes[b]);
    jacobian_pointers.push_back(jacobians[b].data());
  }
  std::vector<double> r(residuals), plus(residuals), minus(residuals);
  ASSERT_TRUE(cost.Evaluate(blocks.data(), r.data(), jacobian_pointers.data()));
  const double step = 1e-6;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    for (int entry = 0; entry < sizes[b]; ++entry) {
      const double saved = blocks[b][entry];
      blocks[b][entry] = saved + step;
      cost.Evaluate(blocks.data(), plus.data(), nullptr);
      blocks[b][entry] = saved - step;
      cost.Evaluate(blocks.data(), minus.data(), nullptr);
      blocks[b][entry] = saved;
      for (int row = 0; row < residuals; ++row) {
        EXPECT_NEAR(jacobians[b][row * sizes[b] + entry], (plus[row] - minus[row]) / (2 * step),
                    1e-5)
            << "block " << b << " entry " << entry << " row " << row;
      }
    }
  }
}

}  // namespace

namespace {

std::vector<Eigen::Vector3f> sorted_points(const Cloud& cloud) {
  std::vector<Eigen::Vector3f> points;
  for (const CloudPoint& p : cloud)
    points.push_back(p.getVector3fMap());
  std::sort(points.begin(), points.end(), [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return points;
}

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

namespace {

// Keyframes 1 m apart along x, each holding one surface point below it.
std::vector<Keyframe> keyframes_along_x(int count) {
  std::vector<Keyframe> keyframes(count);
  for (int i = 0; i < count; ++i) {
    keyframes[i].index = i;
    keyframes[i].pose.translation() = Eigen::Vector3d(i, 0.0, 0.0);
    keyframes[i].corners.reset(new Cloud);
    keyframes[i].surfaces.reset(new Cloud);
    CloudPoint p;
    p.x = 0.f;
    p.y = 0.f;
    p.z = -1.f;
    keyframes[i].surfaces->push_back(p);
  }
  return keyframes;
}

std::vector<float> map_xs(const LocalMap& map) {
  std::vector<float> xs;
  for (const CloudPoint& p : map.surfaces())
    xs.push_back(p.x);
  std::sort(xs.begin(), xs.end());
  return xs;
}

}  // namespace

TEST(LocalMap, LeavesOutTheNewestKeyframesWhileOlderOnesExist) {
  MappingParams params;
  params.local_map_lag_keyframes = 2;
  LocalMap map(params);
  EXPECT_TRUE(map.update(keyframes_along_x(1), Eigen::Vector3d::Zero()));
  EXPECT_EQ(map_xs(map), std::vector<float>({0.f}));  // the only keyframe
  EXPECT_FALSE(map.update(keyframes_along_x(2), Eigen::Vector3d::Zero()));
  EXPECT_TRUE(map.update(keyframes_along_x(5), Eigen::Vector3d::Zero()));
  EXPECT_EQ(map_xs(map), std::vector<float>({0.f, 1.f, 2.f}));
  params.local_map_lag_keyframes = 0;
  LocalMap current(params);
  current.update(keyframes_along_x(5), Eigen::Vector3d::Zero());
  EXPECT_EQ(map_xs(current), std::vector<float>({0.f, 1.f, 2.f, 3.f, 4.f}));
}

TEST(LocalMap, FollowsTheKeyframesNearIt) {
  MappingParams params;
  params.local_map_radius = 2.5;
  params.local_map_lag_keyframes = 0;
  LocalMap map(params);
  const std::vector<Keyframe> keyframes = keyframes_along_x(8);
  map.update(keyframes, Eigen::Vector3d(6.0, 0.0, 0.0));
  EXPECT_EQ(map_xs(map), std::vector<float>({4.f, 5.f, 6.f, 7.f}));
  EXPECT_TRUE(map.update(keyframes, Eigen::Vector3d(2.0, 0.0, 0.0)));  // keyframes leave and enter
  EXPECT_EQ(map_xs(map), std::vector<float>({0.f, 1.f, 2.f, 3.f, 4.f}));
  EXPECT_FALSE(map.update(keyframes, Eigen::Vector3d(2.0, 0.0, 0.0)));
}

TEST(LocalMap, AfterALoopAnswersFromTheOldPlacementUntilTheNewOneIsComplete) {
  MappingParams params;
  params.local_map_lag_keyframes = 0;
  LocalMap map(params);
  std::vector<Keyframe> keyframes = keyframes_along_x(6);
  map.update(keyframes, Eigen::Vector3d::Zero());
  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  correction.translation() = Eigen::Vector3d(0.0, 1.0, 0.0);
  for (Keyframe& keyframe : keyframes)
    keyframe.pose = correction * keyframe.pose;
  map.keyframes_moved(correction);
  // Two keyframes a time: the old placement serves, reached through the inverse correction.
  for (int update = 0; update < 2; ++update) {
    EXPECT_FALSE(map.update(keyframes, Eigen::Vector3d::Zero()));
    EXPECT_TRUE(map.to_placement().isApprox(correction.inverse()));
    for (const CloudPoint& p : map.surfaces())
      EXPECT_FLOAT_EQ(p.y, 0.f);
  }
  EXPECT_TRUE(map.update(keyframes, Eigen::Vector3d::Zero()));
  EXPECT_TRUE(map.to_placement().isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(map_xs(map), std::vector<float>({0.f, 1.f, 2.f, 3.f, 4.f, 5.f}));
  for (const CloudPoint& p : map.surfaces())
    EXPECT_FLOAT_EQ(p.y, 1.f);
}

namespace {

// A corner of a room in the map frame: floor, two walls (every 0.1 m).
CloudPtr room_corner() {
  CloudPtr cloud(new Cloud);
  auto add = [&cloud](float x, float y, float z) {
    CloudPoint p;
    p.x = x;
    p.y = y;
    p.z = z;
    cloud->push_back(p);
  };
  for (float u = -4.f; u <= 4.f; u += 0.1f) {
    for (float v = -4.f; v <= 4.f; v += 0.1f) {
      add(u, v, -1.5f);
      if (v >= -1.5f && v <= 2.f) add(5.f, u, v);
      if (v >= -1.5f && v <= 2.f) add(u, 4.f, v);
    }
  }
  return cloud;
}

}  // namespace

TEST(ScanToMap, MatchesThroughTheOldPlacementAfterALoop) {
  MappingParams params;
  params.local_map_lag_keyframes = 0;
  params.max_iterations = 5;
  LocalMap map(params);
  Keyframe keyframe;
  keyframe.corners.reset(new Cloud);
  keyframe.surfaces = room_corner();
  map.update({keyframe}, Eigen::Vector3d::Zero());

  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  correction.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  correction.translation() = Eigen::Vector3d(2.0, -1.0, 0.1);
  keyframe.pose = correction * keyframe.pose;
  map.keyframes_moved(correction);
  ASSERT_FALSE(map.to_placement().isApprox(Eigen::Isometry3d::Identity()));

  // The sensor 0.5 m from the map origin, in the new frame; the scan sees the room from there.
  Eigen::Isometry3d old_frame_pose = Eigen::Isometry3d::Identity();
  old_frame_pose.translation() = Eigen::Vector3d(0.5, 0.2, 0.0);
  const Eigen::Isometry3d truth = correction * old_frame_pose;
  const CloudPtr scan =
      voxel_filter(*transform_cloud(*room_corner(), old_frame_pose.inverse()), 0.3);
  Eigen::Isometry3d guess = truth;
  guess.translation() += Eigen::Vector3d(0.08, -0.06, 0.03);
  const MapMatchResult result = ScanToMapMatcher(params).match(Cloud(), *scan, map, guess);
  ASSERT_TRUE(result.matched);
  EXPECT_LT((result.pose.translation() - truth.translation()).norm(), 0.01);
  EXPECT_LT(Eigen::AngleAxisd(result.pose.linear().transpose() * truth.linear()).angle(), 0.002);
}

TEST(RegistrationCost, EulerJacobianMatchesFiniteDifferences) {
  const Correspondences matches = some_matches();
  double pose[6] = {0.1, -0.2, 0.3, 0.5, -0.4, 0.2};
  for (MatchKinds kinds : {MatchKinds::kBoth, MatchKinds::kLines, MatchKinds::kPlanes}) {
    const EulerRegistrationCost cost(matches, kinds, 0.5);
    expect_jacobians_match(cost, {pose});
  }
  EXPECT_EQ(EulerRegistrationCost(matches, MatchKinds::kBoth, 0.5).num_residuals(), 6 * 3 + 6);
}

TEST(RegistrationCost, QuaternionJacobianMatchesFiniteDifferences) {
  const Correspondences matches = some_matches();
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  double rotation[4] = {q.x(), q.y(), q.z(), q.w()};
  double translation[3] = {0.3, -0.1, 0.2};
  const QuaternionRegistrationCost cost(matches, 0.5);
  expect_jacobians_match(cost, {rotation, translation});
}

// The cost equals the sum of per-correspondence Huber losses of the point-to-line and
// point-to-plane distances.
TEST(RegistrationCost, CostIsHuberOfDistances) {
  const Correspondences matches = some_matches();
  const double delta = 0.5;
  double pose[6] = {0.1, -0.2, 0.3, 0.5, -0.4, 0.2};
  const EulerRegistrationCost cost(matches, MatchKinds::kBoth, delta);
  std::vector<double> r(cost.num_residuals());
  const double* blocks[] = {pose};
  ASSERT_TRUE(cost.Evaluate(blocks, r.data(), nullptr));
  const Eigen::Isometry3d transform = euler_vector_to_pose(pose);
  auto huber = [delta](double s) {
    return s <= delta * delta ? s : 2 * delta * std::sqrt(s) - delta * delta;
  };
  double expected = 0.0;
  for (const LineMatch& line : matches.lines) {
    const Eigen::Vector3d moved = transform * line.point;
    expected += huber((moved - line.through).cross(line.direction).squaredNorm());
  }
  for (const PlaneMatch& plane : matches.planes) {
    const double distance = plane.normal.dot(transform * plane.point) + plane.offset;
    expected += huber(distance * distance);
  }
  double actual = 0.0;
  for (double value : r)
    actual += value * value;
  EXPECT_NEAR(actual, expected, 1e-9 * expected);
}
