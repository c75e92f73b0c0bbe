#include <gtest/gtest.h>

#include <random>

#include "adaptive_lego_loam/eval/degeneration_evaluation.h"

using namespace adaptive_lego_loam;
using Poses = std::vector<Eigen::Isometry3d>;

namespace {

// Scans 0..count-1: the first `degenerate` of them truly degenerate along x (no information).
std::vector<TrueObservability> truth(int count, int degenerate) {
  std::vector<TrueObservability> scans;
  for (int frame = 0; frame < count; ++frame) {
    TrueObservability& scan = scans.emplace_back();
    scan.frame = frame;
    scan.information = 1e4 * Eigen::Matrix<double, 6, 6>::Identity();
    if (frame < degenerate) scan.information(3, 3) = 0.0;
  }
  return scans;
}

// A run whose scans each claim `covariance`, flagged as `flags` says.
RunDegeneration run(const std::vector<bool>& flags, const Eigen::Matrix3d& covariance) {
  RunDegeneration out;
  for (std::size_t frame = 0; frame < flags.size(); ++frame) {
    RunScan& scan = out.scans.emplace_back();
    scan.frame = static_cast<int>(frame);
    scan.degenerate = flags[frame];
    scan.matched = true;
    scan.translation_covariance = covariance;
  }
  return out;
}

// 1 m a scan along x, truly; the estimate's every step off by an error drawn from N(0, spread).
void drive(int count, const Eigen::Matrix3d& spread, Poses& estimate, Poses& ground_truth) {
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  const Eigen::Matrix3d root = spread.llt().matrixL();
  estimate.assign(1, Eigen::Isometry3d::Identity());
  ground_truth = estimate;
  for (int i = 1; i < count; ++i) {
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
    ground_truth.push_back(ground_truth.back() * step);
    step.translation() += root * Eigen::Vector3d(normal(random), normal(random), normal(random));
    estimate.push_back(estimate.back() * step);
  }
}

}  // namespace

TEST(DegenerationEvaluation, ScoresTheFlagAndTheCovarianceScanByScan) {
  const int count = 2000;
  std::vector<bool> flags(count, false);
  for (int frame = 0; frame < 500; ++frame)
    flags[frame] = frame < 400;  // 400 of the 500 degenerate ones
  for (int frame = 1500; frame < 1600; ++frame)
    flags[frame] = true;  // 100 false alarms
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.04, 0.01, 0.0025).asDiagonal();
  Poses estimate, ground_truth;
  drive(count, covariance, estimate, ground_truth);
  const DegenerationEvaluation evaluation =
      evaluate_degeneration(truth(count, 500), run(flags, covariance), estimate, ground_truth, 0.1);
  EXPECT_EQ(evaluation.degenerate_sigma_m, 0.1);
  EXPECT_EQ(evaluation.scans_compared, count);
  EXPECT_EQ(evaluation.truly_degenerate, 500);
  EXPECT_EQ(evaluation.flagged, 500);
  EXPECT_DOUBLE_EQ(*evaluation.detection.precision, 0.8);
  EXPECT_DOUBLE_EQ(*evaluation.detection.recall, 0.8);
  EXPECT_EQ(evaluation.nees.dof, 3);
  EXPECT_EQ(evaluation.nees.scans, count - 1);  // the first scan has no increment
  EXPECT_NEAR(*evaluation.nees.share_within, 0.95, 0.02);

  const DegenerationEvaluation overconfident = evaluate_degeneration(
      truth(count, 500), run(flags, covariance / 16.0), estimate, ground_truth, 0.1);
  EXPECT_LT(*overconfident.nees.share_within, 0.5);
  EXPECT_NEAR(*overconfident.nees.variance_scale, 16.0, 2.0);
}

TEST(DegenerationEvaluation, UnmatchedScansAndScansWithoutTruthOrPosesAreLeftOut) {
  const Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  RunDegeneration scans = run({true, true, false, false, false}, covariance);
  scans.scans[1].matched = false;
  Poses estimate, ground_truth;
  drive(4, covariance, estimate, ground_truth);  // no pose for scan 4
  const DegenerationEvaluation evaluation =
      evaluate_degeneration(truth(4, 1), scans, estimate, ground_truth, 0.1);  // nor truth
  EXPECT_EQ(evaluation.scans_compared, 3);                                     // 0, 2, 3
  EXPECT_EQ(evaluation.detection.true_positives, 1);
  EXPECT_EQ(evaluation.detection.true_negatives, 2);
  EXPECT_EQ(evaluation.nees.scans, 2);  // 2 and 3
}

TEST(DegenerationEvaluation, WithoutTheCovarianceTheWeakestDirectionIsScoredAlone) {
  RunDegeneration scans = run({false, false, false}, Eigen::Matrix3d::Identity());
  scans.uncertainty_source = UncertaintySource::kCorrespondenceWeakest;
  for (RunScan& scan : scans.scans) {
    scan.translation_covariance.reset();
    scan.weak_direction = Eigen::Vector3d::UnitY();
    scan.weak_sigma_m = 0.5;
  }
  scans.scans[2].weak_sigma_m = INFINITY;
  Poses ground_truth(3, Eigen::Isometry3d::Identity()), estimate = ground_truth;
  estimate[1].translation() << 3.0, 1.0, 0.0;  // 2 sigmas along y; x is not scored
  estimate[2] = estimate[1];
  estimate[2].translation().y() += 100.0;  // along a direction claimed free
  const DegenerationEvaluation evaluation =
      evaluate_degeneration(truth(3, 0), scans, estimate, ground_truth, 0.1);
  EXPECT_EQ(evaluation.nees.dof, 1);
  EXPECT_EQ(evaluation.nees.scans, 2);
  EXPECT_EQ(evaluation.nees.within, 1);
  EXPECT_EQ(evaluation.nees.below, 1);
  EXPECT_DOUBLE_EQ(*evaluation.nees.median_nees, 2.0);  // (4 + 0) / 2
}
