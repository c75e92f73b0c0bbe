// A pose's covariance carried along motions: the lever arm of a heading's uncertainty, the cap on
// directions lost, and what a chain added between two of its poses.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/core/odometry/covariance_propagation.h"

using namespace adaptive_lego_loam;

namespace {

Eigen::Isometry3d straight(double metres) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translation().x() = metres;
  return motion;
}

Eigen::Isometry3d turn_and_move(double yaw_deg, const Eigen::Vector3d& translation) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() =
      Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  motion.translation() = translation;
  return motion;
}

}  // namespace

// A heading known to 1 deg, then 10 m straight on: the position is known across the way to
// 10 m x 1 deg, along it as before.
TEST(CovariancePropagation, AHeadingsUncertaintyBecomesCrossTrackAfterDriving) {
  Matrix6d heading = Matrix6d::Zero();
  const double yaw_sigma = M_PI / 180.0;
  heading(2, 2) = yaw_sigma * yaw_sigma;
  const Matrix6d after = compose_covariance(heading, straight(10.0), Matrix6d::Zero());
  EXPECT_NEAR(after(4, 4), std::pow(10.0 * yaw_sigma, 2), 1e-9);  // y, across
  EXPECT_NEAR(after(3, 3), 0.0, 1e-12);                           // x, along
  EXPECT_NEAR(after(2, 2), heading(2, 2), 1e-12);
}

TEST(CovariancePropagation, MotionsAddTheirOwnCovariance) {
  Matrix6d step = Matrix6d::Identity() * 1e-4;
  Matrix6d covariance = Matrix6d::Zero();
  for (int scan = 0; scan < 5; ++scan)
    covariance = compose_covariance(covariance, Eigen::Isometry3d::Identity(), step);
  EXPECT_TRUE(covariance.isApprox(5.0 * step, 1e-12));
}

// A direction lost stays at the unknown variance, however many scans lose it again.
TEST(CovariancePropagation, ALostDirectionIsHeldAtTheUnknownVariance) {
  Matrix6d lost = Matrix6d::Identity() * 1e-4;
  lost(3, 3) = 1e4;
  Matrix6d covariance = Matrix6d::Zero();
  for (int scan = 0; scan < 20; ++scan)
    covariance = compose_covariance(covariance, straight(1.0), lost, 1e4);
  EXPECT_NEAR(covariance(3, 3), 1e4, 1e-6);
  EXPECT_LT(covariance(4, 4), 1.0);
}

TEST(CovariancePropagation, WhatAChainAddedIsRecoveredBetweenTwoOfItsPoses) {
  Matrix6d start = Matrix6d::Identity() * 2e-4;
  start(2, 2) = 3e-4;
  Matrix6d step = Matrix6d::Identity() * 1e-5;
  step(3, 4) = step(4, 3) = 4e-6;
  const Eigen::Isometry3d first = turn_and_move(5.0, {1.0, 0.2, 0.0});
  const Eigen::Isometry3d second = turn_and_move(-3.0, {0.8, -0.1, 0.05});
  const Matrix6d middle = compose_covariance(start, first, step);
  const Matrix6d end = compose_covariance(middle, second, step);
  // From the start to the end: the two steps, the first one carried along the second motion.
  const Matrix6d added = covariance_added(start, first * second, end);
  EXPECT_TRUE(added.isApprox(compose_covariance(step, second, step), 1e-9));
  EXPECT_TRUE(covariance_added(middle, second, end).isApprox(step, 1e-9));
}
