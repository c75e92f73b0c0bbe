// The building blocks of odometry and mapping: the KD-tree and the voxel map against a brute-force
// search, and the registration cost functions' analytic Jacobians against finite differences.

#include <gtest/gtest.h>
#include <pcl/filters/voxel_grid.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/mapping/scan_to_map.h"
#include "adaptive_lego_loam/core/mapping/vertical_structure.h"
#include "adaptive_lego_loam/core/odometry/residuals.h"
#include "adaptive_lego_loam/core/spatial/kdtree.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"
#include "adaptive_lego_loam/core/spatial/voxel_map.h"

using namespace adaptive_lego_loam;

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

// Scan-to-map on a map of one keyframe: in the map at once, five correspondence searches.
MappingParams one_keyframe_params() {
  MappingParams params;
  params.local_map_lag_keyframes = 0;
  params.max_iterations = 5;
  return params;
}

// A keyframe at `pose` holding the room corner as its surfaces.
Keyframe room_keyframe(const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) {
  Keyframe keyframe;
  keyframe.pose = pose;
  keyframe.corners = pack(Cloud());
  keyframe.surfaces = pack(*room_corner());
  return keyframe;
}

}  // namespace

TEST(ScanToMap, MatchesThroughTheOldPlacementAfterALoop) {
  const MappingParams params = one_keyframe_params();
  LocalMap map(params);
  Keyframe keyframe = room_keyframe();
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

TEST(ScanToMap, TheVerticalPriorKeepsWallsUprightAgainstATiltedMap) {
  // A map that drifted 2 deg in roll, and a level sensor at its origin: the scan alone follows
  // the map's tilt; with the prior the scan's walls stay vertical and the pose stays level.
  MappingParams params = one_keyframe_params();
  LocalMap map(params);
  Eigen::Isometry3d tilted = Eigen::Isometry3d::Identity();
  tilted.linear() = Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()).matrix();
  map.update({room_keyframe(tilted)}, Eigen::Vector3d::Zero());
  const CloudPtr scan = voxel_filter(*room_corner(), 0.3);
  auto roll_deg = [](const MapMatchResult& result) {
    const Eigen::Vector3d up = result.pose.linear() * Eigen::Vector3d::UnitZ();
    return std::acos(std::min(1.0, up.z())) * 180.0 / M_PI;
  };

  const MapMatchResult free =
      ScanToMapMatcher(params).match(Cloud(), *scan, map, Eigen::Isometry3d::Identity());
  ASSERT_TRUE(free.matched);
  EXPECT_NEAR(roll_deg(free), 2.0, 0.2);

  params.vertical_prior_weight = 100.0;
  const std::vector<Eigen::Vector3d> walls =
      wall_normals(*room_corner(), Eigen::Matrix3d::Identity(), params.vertical_prior_max_tilt_deg);
  ASSERT_FALSE(walls.empty());
  const MapMatchResult held = ScanToMapMatcher(params).match(
      Cloud(), *scan, map, Eigen::Isometry3d::Identity(), std::nullopt, walls);
  ASSERT_TRUE(held.matched);
  EXPECT_LT(roll_deg(held), 0.5);
}

// A loop's refinement spreads the match over scans: an iteration at a time, it ends exactly where
// the whole match does.
TEST(ScanToMap, AMatchAnIterationAtATimeEndsWhereTheWholeMatchDoes) {
  const MappingParams params = one_keyframe_params();
  LocalMap map(params);
  map.update({room_keyframe()}, Eigen::Vector3d::Zero());
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translation() = Eigen::Vector3d(0.5, 0.2, 0.0);
  const CloudPtr scan = voxel_filter(*transform_cloud(*room_corner(), truth.inverse()), 0.3);
  Eigen::Isometry3d guess = truth;
  guess.translation() += Eigen::Vector3d(0.15, -0.1, 0.05);
  const MapMatchResult whole = ScanToMapMatcher(params).match(Cloud(), *scan, map, guess);
  ASSERT_TRUE(whole.matched);
  ASSERT_GE(whole.iterations, 2);

  const Cloud no_corners;  // referenced by the match: it must outlive it
  SteppedMapMatch stepped(params, no_corners, *scan, map, guess);
  EXPECT_FALSE(stepped.result().matched);
  EXPECT_EQ(stepped.result().pose.matrix(), guess.matrix());
  int iterations = 0;
  while (!stepped.done()) {
    stepped.iterate();
    ++iterations;
    EXPECT_EQ(stepped.result().iterations, iterations);
    ASSERT_LE(iterations, params.max_iterations);
  }
  stepped.iterate();  // done: nothing more
  const MapMatchResult result = stepped.result();
  EXPECT_EQ(iterations, whole.iterations);
  EXPECT_EQ(result.pose.matrix(), whole.pose.matrix());
  EXPECT_EQ(result.plane_matches, whole.plane_matches);
  EXPECT_EQ(result.smallest_eigenvalue, whole.smallest_eigenvalue);
  EXPECT_LT((result.pose.translation() - truth.translation()).norm(), 0.01);
}

TEST(ScanToMap, AMatchOnAnEmptyMapIsDoneAtOnceAtTheGuess) {
  const MappingParams params = one_keyframe_params();
  const LocalMap map(params);
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  guess.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
  const Cloud no_corners;
  const CloudPtr surfaces = room_corner();
  const SteppedMapMatch stepped(params, no_corners, *surfaces, map, guess);
  EXPECT_TRUE(stepped.done());
  EXPECT_FALSE(stepped.result().matched);
  EXPECT_EQ(stepped.result().pose.matrix(), guess.matrix());
}

namespace {

// A corridor along x: a floor and two walls, nothing that fixes the motion along it. The floor
// and the walls stop short of each other: where two surfaces meet, a plane fitted to a few of
// both leans along the corridor and measures it falsely.
CloudPtr corridor() {
  CloudPtr cloud(new Cloud);
  auto add = [&cloud](float x, float y, float z) {
    CloudPoint p;
    p.x = x;
    p.y = y;
    p.z = z;
    cloud->push_back(p);
  };
  for (float x = -20.f; x <= 20.f; x += 0.1f) {
    for (float v = -0.75f; v <= 0.75f; v += 0.1f) {
      add(x, v, -1.5f);
      add(x, -1.5f, v + 0.5f);
      add(x, 1.5f, v + 0.5f);
    }
  }
  return cloud;
}

// Known to a millimetre in every direction.
MotionPrior exact_prior(const Eigen::Isometry3d& motion) {
  MotionPrior prior;
  prior.motion = motion;
  prior.information = Matrix6d::Identity() * 1e6;
  return prior;
}

}  // namespace

TEST(ScanToMap, APriorHoldsTheDirectionTheSceneLeavesOpenAndOnlyThat) {
  MappingParams params = one_keyframe_params();
  params.residual_sigma = 0.05;
  LocalMap map(params);
  Keyframe keyframe;
  keyframe.corners = pack(Cloud());
  keyframe.surfaces = pack(*corridor());
  map.update({keyframe}, Eigen::Vector3d::Zero());
  // The sensor moved 1 m along the corridor; the guess says 0.6 m, the prior 1.0 m.
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translation() = Eigen::Vector3d(1.0, 0.1, 0.0);
  const CloudPtr scan = voxel_filter(*transform_cloud(*corridor(), truth.inverse()), 0.3);
  Eigen::Isometry3d guess = truth;
  guess.translation() += Eigen::Vector3d(-0.4, 0.05, 0.02);

  const MapMatchResult alone = ScanToMapMatcher(params).match(Cloud(), *scan, map, guess);
  ASSERT_TRUE(alone.matched);
  // The scene fixes y and z, not x: the LiDAR leaves x at its guess and says so.
  EXPECT_NEAR(alone.pose.translation().y(), 0.1, 0.01);
  EXPECT_NEAR(alone.pose.translation().x(), 0.6, 0.01);
  EXPECT_GT(observability(alone.information).weakest_sigma(), 1.0);
  EXPECT_GT(std::fabs(observability(alone.information).weakest_direction().x()), 0.99);

  SensorPriors sensors;
  sensors.previous = Eigen::Isometry3d::Identity();
  sensors.motion = exact_prior(truth);
  const MapMatchResult held =
      ScanToMapMatcher(params).match(Cloud(), *scan, map, guess, std::nullopt, {}, sensors);
  ASSERT_TRUE(held.matched);
  EXPECT_TRUE(held.motion_prior);
  EXPECT_NEAR(held.pose.translation().x(), 1.0, 0.01);
  EXPECT_NEAR(held.pose.translation().y(), 0.1, 0.01);
  // The LiDAR's own information is the same: the prior is not counted as the scene's.
  EXPECT_GT(observability(held.information).weakest_sigma(), 1.0);
  // The prior's is counted apart, on the open direction only: with it the estimate knows x.
  EXPECT_TRUE(alone.prior_information.isZero());
  EXPECT_GT(held.prior_information(3, 3), 0.9e6);
  EXPECT_LT(held.prior_information(4, 4), 0.01 * held.prior_information(3, 3));
  EXPECT_LT(observability(held.information + held.prior_information).weakest_sigma(), 0.01);

  // A prior that is wrong where the scene sees (0.3 m off in y) does not move the match there.
  Eigen::Isometry3d wrong = truth;
  wrong.translation().y() += 0.3;
  sensors.motion = exact_prior(wrong);
  const MapMatchResult kept =
      ScanToMapMatcher(params).match(Cloud(), *scan, map, guess, std::nullopt, {}, sensors);
  EXPECT_NEAR(kept.pose.translation().y(), 0.1, 0.01);
}

TEST(ScanToMap, InAWellConstrainedRoomThePriorChangesNothing) {
  MappingParams params = one_keyframe_params();
  LocalMap map(params);
  map.update({room_keyframe()}, Eigen::Vector3d::Zero());
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translation() = Eigen::Vector3d(0.5, 0.2, 0.0);
  const CloudPtr scan = voxel_filter(*transform_cloud(*room_corner(), truth.inverse()), 0.3);
  Eigen::Isometry3d guess = truth;
  guess.translation() += Eigen::Vector3d(0.1, -0.05, 0.02);
  const MapMatchResult alone = ScanToMapMatcher(params).match(Cloud(), *scan, map, guess);
  SensorPriors sensors;
  Eigen::Isometry3d off = truth;
  off.translation().x() += 0.2;
  sensors.motion = exact_prior(off);
  const MapMatchResult with_prior =
      ScanToMapMatcher(params).match(Cloud(), *scan, map, guess, std::nullopt, {}, sensors);
  EXPECT_FALSE(with_prior.motion_prior);
  EXPECT_EQ(with_prior.pose.matrix(), alone.pose.matrix());
}

TEST(ScanToMap, GravityHoldsTheAttitudeAgainstATiltedMap) {
  // As the vertical-structure prior: a map that drifted 2 deg in roll, a level sensor whose IMU
  // says so; gravity pulls the pose level.
  MappingParams params = one_keyframe_params();
  LocalMap map(params);
  Eigen::Isometry3d tilted = Eigen::Isometry3d::Identity();
  tilted.linear() = Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()).matrix();
  map.update({room_keyframe(tilted)}, Eigen::Vector3d::Zero());
  const CloudPtr scan = voxel_filter(*room_corner(), 0.3);
  SensorPriors sensors;
  GravityPrior gravity;
  gravity.up = Eigen::Vector3d::UnitZ();
  gravity.covariance = Eigen::Matrix3d::Identity() * 1e-8;
  sensors.gravity = gravity;
  params.gravity_sigma_deg = 0.01;
  params.residual_sigma = 0.05;
  const MapMatchResult held = ScanToMapMatcher(params).match(
      Cloud(), *scan, map, Eigen::Isometry3d::Identity(), std::nullopt, {}, sensors);
  ASSERT_TRUE(held.matched);
  const Eigen::Vector3d up = held.pose.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, up.z())) * 180.0 / M_PI, 0.5);
}
