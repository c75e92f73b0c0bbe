#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"

using namespace adaptive_lego_loam;

namespace {

Eigen::Isometry3d motion(double x, double yaw_deg) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.translation().x() = x;
  m.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  return m;
}

OdometryParams bounds(double max_speed, double max_turn_rate_deg) {
  OdometryParams params;
  params.max_speed = max_speed;
  params.max_turn_rate_deg = max_turn_rate_deg;
  return params;
}

}  // namespace

TEST(PlausibleMotion, SpeedAndTurnRateAreBoundedOverOneScanPeriod) {
  const OdometryParams params = bounds(50.0, 360.0);  // 5 m and 36 deg in 0.1 s
  EXPECT_TRUE(plausible_motion(motion(4.9, 0.0), params, 0.1));
  EXPECT_FALSE(plausible_motion(motion(5.1, 0.0), params, 0.1));
  EXPECT_TRUE(plausible_motion(motion(0.0, -35.0), params, 0.1));
  EXPECT_FALSE(plausible_motion(motion(0.0, -37.0), params, 0.1));
  // The same motions over a longer period (a 5 Hz sensor) are slower.
  EXPECT_TRUE(plausible_motion(motion(5.1, 37.0), params, 0.2));
}

TEST(PlausibleMotion, ZeroTurnsABoundOff) {
  EXPECT_TRUE(plausible_motion(motion(1000.0, 0.0), bounds(0.0, 360.0), 0.1));
  EXPECT_TRUE(plausible_motion(motion(0.0, 170.0), bounds(50.0, 0.0), 0.1));
}

TEST(PlausibleMotion, ANonFiniteMotionIsNeverPlausible) {
  Eigen::Isometry3d broken = Eigen::Isometry3d::Identity();
  broken.translation().y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(plausible_motion(broken, bounds(0.0, 0.0), 0.1));
  broken = Eigen::Isometry3d::Identity();
  broken.linear()(0, 1) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(plausible_motion(broken, bounds(0.0, 0.0), 0.1));
}
