#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <stdexcept>

#include "adaptive_lego_loam/eval/covariance_consistency.h"

using namespace adaptive_lego_loam;

namespace {

// A correlated covariance, long along a tilted direction (as a tunnel's axis would be).
Eigen::Matrix3d tilted_covariance() {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  return rotation * Eigen::Vector3d(4.0, 0.01, 0.0004).asDiagonal() * rotation.transpose();
}

// NEES of `count` errors drawn from N(0, truth), against the claimed covariance.
std::vector<double> nees_sample(const Eigen::Matrix3d& truth, const Eigen::Matrix3d& claimed,
                                int count) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  const Eigen::Matrix3d root = truth.llt().matrixL();
  std::vector<double> values;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d unit(normal(random), normal(random), normal(random));
    values.push_back(nees(root * unit, claimed));
  }
  return values;
}

Eigen::Isometry3d pose(double x, double y, double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() << x, y, 0.0;
  return pose;
}

}  // namespace

TEST(CovarianceConsistency, ChiSquareBoundsAreTheTabulatedOnes) {
  const ChiSquareBounds three = chi_square_bounds(3);
  EXPECT_NEAR(three.lower, 0.2158, 1e-4);
  EXPECT_NEAR(three.upper, 9.3484, 1e-4);
  const ChiSquareBounds one = chi_square_bounds(1);
  EXPECT_NEAR(one.lower, 0.000982, 1e-6);
  EXPECT_NEAR(one.upper, 5.0239, 1e-4);
  EXPECT_NEAR(chi_square_median(3), 2.366, 1e-3);
  EXPECT_THROW(chi_square_bounds(0), std::invalid_argument);
  EXPECT_THROW(chi_square_bounds(3, 1.0), std::invalid_argument);
}

TEST(CovarianceConsistency, NeesIsTheErrorSquaredInSigmas) {
  const Eigen::Matrix3d covariance = Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal();
  EXPECT_NEAR(nees(Eigen::Vector3d(2.0, 1.0, 0.5), covariance), 3.0, 1e-12);
  EXPECT_THROW(nees(Eigen::Vector3d::Ones(), Eigen::Matrix3d::Zero()), std::invalid_argument);
  EXPECT_THROW(nees(Eigen::Vector2d::Ones(), covariance), std::invalid_argument);
}

TEST(CovarianceConsistency, AConsistentCovarianceHasAbout95PercentWithinTheBounds) {
  const Eigen::Matrix3d covariance = tilted_covariance();
  const NeesSummary summary = summarize_nees(nees_sample(covariance, covariance, 4000), 3);
  EXPECT_EQ(summary.scans, 4000);
  EXPECT_EQ(summary.below + summary.within + summary.above, 4000);
  EXPECT_NEAR(*summary.share_within, 0.95, 0.015);
  EXPECT_NEAR(double(summary.above) / summary.scans, 0.025, 0.01);
  EXPECT_NEAR(*summary.variance_scale, 1.0, 0.1);
}

TEST(CovarianceConsistency, AnOverconfidentCovarianceHasFarFewerAndShowsByHowMuch) {
  const Eigen::Matrix3d truth = tilted_covariance();
  const NeesSummary summary = summarize_nees(nees_sample(truth, truth / 9.0, 4000), 3);
  EXPECT_LT(*summary.share_within, 0.6);
  EXPECT_GT(double(summary.above) / summary.scans, 0.4);
  EXPECT_NEAR(*summary.variance_scale, 9.0, 1.0);
  // Too cautious: the error falls below the lower bound instead.
  const NeesSummary cautious = summarize_nees(nees_sample(truth, 100.0 * truth, 4000), 3);
  EXPECT_GT(double(cautious.below) / cautious.scans, 0.9);
}

TEST(CovarianceConsistency, AnEmptySampleHasNoShare) {
  const NeesSummary summary = summarize_nees({}, 3);
  EXPECT_EQ(summary.scans, 0);
  EXPECT_FALSE(summary.share_within);
  EXPECT_FALSE(summary.variance_scale);
  EXPECT_THROW(summarize_nees({1.0, NAN}, 3), std::invalid_argument);
}

TEST(CovarianceConsistency, TheIncrementErrorIsInTheLaterScansSensorFrame) {
  // Truly 1 m forward while turned 90 deg left; estimated 1.2 m forward and 0.1 m left: the error
  // is along the sensor's x and y, whatever the world's axes are.
  const Eigen::Isometry3d start = pose(5.0, 3.0, M_PI / 2);
  const Eigen::Vector3d error = increment_translation_error(start, start * pose(1.2, 0.1, 0.0),
                                                            start, start * pose(1.0, 0.0, 0.0));
  EXPECT_TRUE(error.isApprox(Eigen::Vector3d(0.2, 0.1, 0.0), 1e-12)) << error.transpose();
  // The same estimated motion from an estimate that had drifted: only the motion counts.
  const Eigen::Vector3d drifted =
      increment_translation_error(pose(9.0, 1.0, 0.3), pose(9.0, 1.0, 0.3) * pose(1.2, 0.1, 0.0),
                                  start, start * pose(1.0, 0.0, 0.0));
  EXPECT_TRUE(drifted.isApprox(error, 1e-12));
}
