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

// Keyframes 1 m apart along x, each holding one surface point below it.
std::vector<Keyframe> keyframes_along_x(int count) {
  std::vector<Keyframe> keyframes(count);
  for (int i = 0; i < count; ++i) {
    keyframes[i].index = i;
    keyframes[i].pose.translation() = Eigen::Vector3d(i, 0.0, 0.0);
    Cloud surface;
    CloudPoint p;
    p.x = 0.f;
    p.y = 0.f;
    p.z = -1.f;
    surface.push_back(p);
    keyframes[i].corners = pack(Cloud());
    keyframes[i].surfaces = pack(surface);
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

TEST(LocalMap, KeyframesRemovedFromTheListLeaveTheMapAndTheOthersStayPlaced) {
  MappingParams params;
  params.local_map_lag_keyframes = 0;
  LocalMap map(params);
  std::vector<Keyframe> keyframes = keyframes_along_x(6);
  map.update(keyframes, Eigen::Vector3d::Zero());
  // Keyframes 2 and 3 go; 4 and 5 become 2 and 3.
  keyframes.erase(keyframes.begin() + 2, keyframes.begin() + 4);
  for (int i = 0; i < static_cast<int>(keyframes.size()); ++i)
    keyframes[i].index = i;
  map.keyframes_removed(2, 2);
  EXPECT_EQ(map_xs(map), std::vector<float>({0.f, 1.f, 4.f, 5.f}));
  // Nothing to put in or take out: the renumbered keyframes are the ones placed.
  EXPECT_FALSE(map.update(keyframes, Eigen::Vector3d::Zero()));
  EXPECT_EQ(map_xs(map), std::vector<float>({0.f, 1.f, 4.f, 5.f}));
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
