// Scan-to-map's guess when the scan-to-scan motion is implausible (MappingParams'
// max_motion_change): on a highway whose guard-rail posts repeat every 2 m, a truck driving along
// drags the scan-to-scan estimate to standstill, and scan-to-map, started there, agrees with it.

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "adaptive_lego_loam/core/pipeline/lidar_mapping.h"

using namespace adaptive_lego_loam;

namespace {

constexpr double kPostSpacing = 2.0;  // m, as real guard-rail posts
constexpr double kSpeed = 2.0;        // m per scan: each scan sees the same picture
constexpr double kRange = 40.0;       // m: what a scan sees ahead and behind

void add(Cloud& cloud, double x, double y, double z) {
  CloudPoint point;
  point.x = static_cast<float>(x);
  point.y = static_cast<float>(y);
  point.z = static_cast<float>(z);
  point.intensity = 0.0f;
  cloud.push_back(point);
}

// The features of a straight road seen from x = `sensor_x`, in the sensor frame: the road
// surface, a rail on each side (surfaces), a post every kPostSpacing behind each rail (edges).
FeatureSet highway_features(double sensor_x) {
  FeatureSet features;
  const double first = std::ceil((sensor_x - kRange) / kPostSpacing) * kPostSpacing;
  for (double x = first; x <= sensor_x + kRange; x += kPostSpacing) {
    for (double side : {-1.0, 1.0}) {
      for (double z = -1.7; z <= -0.7; z += 0.1)
        add(*features.less_sharp, x - sensor_x, side * 6.3, z);
    }
  }
  for (double x = first; x <= sensor_x + kRange; x += 0.5) {
    for (double y = -5.5; y <= 5.5; y += 0.5)
      add(*features.less_flat, x - sensor_x, y, -1.7);
    for (double side : {-1.0, 1.0}) {
      for (double z = -1.2; z <= -0.9; z += 0.1)
        add(*features.less_flat, x - sensor_x, side * 6.0, z);
    }
  }
  *features.sharp = *features.less_sharp;
  *features.flat = *features.less_flat;
  return features;
}

Eigen::Isometry3d along_x(double x) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation().x() = x;
  return pose;
}

// Mapping without loop closure, of a sensor whose sweeps come de-skewed.
Config gated_config(double max_motion_change, int max_gated_scans = 0) {
  Config config;
  config.mapping.max_motion_change = max_motion_change;
  config.mapping.max_gated_scans = max_gated_scans;
  config.mapping.max_motion_change_deg = 5.0;
  config.loop_closure.enabled = false;
  config.sensor.deskewed = true;
  return config;
}

// Drives at kSpeed for `scans` scans; the odometry reports standstill on the scan `stalled`.
// Returns the mapped x of that scan and whether the gate fired there.
std::pair<double, bool> mapped_x_when_odometry_stalls(const Config& config, int stalled) {
  LidarMapping mapping(config);
  MappingOutput out;
  double odometry_x = 0.0;
  for (int scan = 0; scan <= stalled; ++scan) {
    if (scan > 0 && scan != stalled) odometry_x += kSpeed;
    mapping.process(highway_features(scan * kSpeed), along_x(odometry_x), 0.1 * scan, std::nullopt,
                    out);
    if (scan < stalled) {
      EXPECT_FALSE(out.motion_gated) << "scan " << scan;
    }
  }
  return {out.pose.translation().x(), out.motion_gated};
}

}  // namespace

TEST(MotionGate, StalledOdometryOnRepeatingPostsKeepsTheVelocity) {
  const int stalled = 6;
  for (int max_gated_scans : {0, 3}) {
    const auto [gated_x, gated] =
        mapped_x_when_odometry_stalls(gated_config(0.3, max_gated_scans), stalled);
    EXPECT_TRUE(gated) << "max_gated_scans " << max_gated_scans;
    EXPECT_NEAR(gated_x, stalled * kSpeed, 0.05) << "max_gated_scans " << max_gated_scans;
  }
}

namespace {

// The vehicle drives at kSpeed, then stands still (an abrupt stop the gate cannot tell from a
// dragged odometry); returns, per scan after the stop, the mapped step and whether it was gated.
std::vector<std::pair<double, bool>> steps_after_a_stop(const Config& config) {
  const int driving = 6, standing = 8;
  LidarMapping mapping(config);
  MappingOutput out;
  std::vector<std::pair<double, bool>> steps;
  double x = 0.0, mapped_x = 0.0;
  for (int scan = 0; scan < driving + standing; ++scan) {
    if (scan > 0 && scan < driving) x += kSpeed;
    mapping.process(highway_features(x), along_x(x), 0.1 * scan, std::nullopt, out);
    if (scan >= driving)
      steps.emplace_back(out.pose.translation().x() - mapped_x, out.motion_gated);
    mapped_x = out.pose.translation().x();
  }
  return steps;
}

}  // namespace

TEST(MotionGate, NeverLettingGoKeepsDrivingAfterAStop) {
  for (const auto& [step, gated] : steps_after_a_stop(gated_config(0.3, 0))) {
    EXPECT_TRUE(gated);
    EXPECT_NEAR(step, kSpeed, 0.05);
  }
}

TEST(MotionGate, LetsTheOdometryBackInAfterMaxGatedScans) {
  const int max_gated_scans = 3;
  const auto steps = steps_after_a_stop(gated_config(0.3, max_gated_scans));
  for (int scan = 0; scan < static_cast<int>(steps.size()); ++scan) {
    const auto [step, gated] = steps[scan];
    const bool held = scan < max_gated_scans;
    EXPECT_EQ(gated, held) << "scan " << scan << " after the stop";
    EXPECT_NEAR(step, held ? kSpeed : 0.0, 0.05) << "scan " << scan << " after the stop";
  }
}

TEST(MotionGate, WithoutTheGateTheMapAgreesWithTheStalledOdometry) {
  // Shows what the gate is for: the repeating scene matches just as well one post behind.
  const int stalled = 6;
  const auto [x, gated] = mapped_x_when_odometry_stalls(gated_config(0.0), stalled);
  EXPECT_FALSE(gated);
  EXPECT_NEAR(x, (stalled - 1) * kSpeed, 0.05);
}

TEST(MotionGate, SmoothAccelerationPassesTheGate) {
  LidarMapping mapping(gated_config(0.3));
  MappingOutput out;
  double x = 0.0, speed = 1.0;
  for (int scan = 0; scan < 8; ++scan) {
    if (scan > 0) {
      x += speed;
      speed += 0.2;  // 20 m/s^2 at 10 Hz: hard, but a vehicle can
    }
    mapping.process(highway_features(x), along_x(x), 0.1 * scan, std::nullopt, out);
    EXPECT_FALSE(out.motion_gated) << "scan " << scan;
    EXPECT_NEAR(out.pose.translation().x(), x, 0.05) << "scan " << scan;
  }
}

// Without a solve to re-orthonormalise it (mapping off), a gated scan composes the pose with the
// velocity taken from the pose itself: its rounding must not grow scan after scan until the
// rotation is no rotation and the positions run off to infinity.
TEST(MotionGate, AStreakOfGatedScansKeepsThePoseARotation) {
  Config config = gated_config(0.3, 0);
  config.mapping.enabled = false;
  LidarMapping mapping(config);
  MappingOutput out;
  Eigen::Isometry3d turn = along_x(kSpeed);
  turn.linear() = (Eigen::AngleAxisd(0.03, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  Eigen::Isometry3d odometry = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d kept_turning = Eigen::Isometry3d::Identity();
  const int driving = 6, standing = 300;  // the odometry stops: every scan after is gated
  for (int scan = 0; scan < driving + standing; ++scan) {
    if (scan > 0 && scan < driving) odometry = odometry * turn;
    if (scan > 0) kept_turning = kept_turning * turn;
    mapping.process(highway_features(0.0), odometry, 0.1 * scan, std::nullopt, out);
    if (scan >= driving) {
      ASSERT_TRUE(out.motion_gated) << "scan " << scan;
    }
  }
  const Eigen::Matrix3d rotation = out.pose.linear();
  EXPECT_LT((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  // The gate kept the last velocity all along.
  EXPECT_LT((out.pose.translation() - kept_turning.translation()).norm(), 1e-6);
  EXPECT_LT((rotation - kept_turning.linear()).norm(), 1e-9);
}

// A node turns the per-scan trajectory off to bound its memory: the mapping is the same without
// it, and nothing is kept per scan.
TEST(LidarMapping, WithoutTheTrajectoryMapsTheSameAndKeepsNoPosePerScan) {
  const Config config = gated_config(0.3);
  LidarMapping kept(config), not_kept(config);
  not_kept.keep_trajectory(false);
  MappingOutput kept_out, not_kept_out;
  const int scans = 12;
  for (int scan = 0; scan < scans; ++scan) {
    const double x = scan * kSpeed;
    kept.process(highway_features(x), along_x(x), 0.1 * scan, std::nullopt, kept_out);
    not_kept.process(highway_features(x), along_x(x), 0.1 * scan, std::nullopt, not_kept_out);
    EXPECT_TRUE(kept_out.pose.isApprox(not_kept_out.pose, 1e-12)) << "scan " << scan;
  }
  EXPECT_EQ(kept.trajectory().size(), static_cast<std::size_t>(scans));
  EXPECT_TRUE(not_kept.trajectory().empty());
  EXPECT_EQ(kept.keyframes().size(), not_kept.keyframes().size());
}
