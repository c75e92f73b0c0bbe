#include <gtest/gtest.h>

#include <stdexcept>

#include "adaptive_lego_loam/eval/degeneration_detection.h"

using namespace adaptive_lego_loam;
using Information = Eigen::Matrix<double, 6, 6>;

namespace {

// A tunnel along x: everything fixed (1e4 per unit), the translation along x by `along_x`.
Information tunnel(double along_x) {
  Information information = 1e4 * Information::Identity();
  information(3, 3) = along_x;
  return information;
}

}  // namespace

TEST(DegenerationDetection, TheTruthIsDegenerateWhereATranslationSigmaExceedsTheThreshold) {
  EXPECT_FALSE(truly_degenerate(tunnel(1e4), 0.1));
  EXPECT_FALSE(truly_degenerate(tunnel(101.0), 0.1));  // sigma 0.0995 m
  EXPECT_TRUE(truly_degenerate(tunnel(99.0), 0.1));    // sigma 0.1005 m
  EXPECT_TRUE(truly_degenerate(tunnel(0.0), 0.1));
  EXPECT_TRUE(truly_degenerate(Information::Zero(), 0.1));
  EXPECT_FALSE(truly_degenerate(tunnel(99.0), 0.2));
}

TEST(DegenerationDetection, TheRotationIsMarginalisedOut) {
  // x fixed directly, but only together with the yaw it is coupled to: sigma along x is then
  // that of the Schur complement, 1 / sqrt(1e4 - 1e4^2 / (1e4 + 1)) ~ 1 m.
  Information information = 1e4 * Information::Identity();
  information(2, 2) = 1e4 + 1.0;
  information(2, 3) = information(3, 2) = 1e4;
  EXPECT_TRUE(truly_degenerate(information, 0.1));
  information(2, 3) = information(3, 2) = 0.0;
  EXPECT_FALSE(truly_degenerate(information, 0.1));
}

TEST(DegenerationDetection, KnownFlagsGiveKnownPrecisionAndRecall) {
  // 6 truly degenerate scans of which 4 flagged; 2 flagged that are not; 3 quiet ones.
  const std::vector<bool> truth{1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0};
  const std::vector<bool> flags{1, 1, 1, 1, 0, 0, 1, 1, 0, 0, 0};
  const DetectionScore score = score_detection(truth, flags);
  EXPECT_EQ(score.true_positives, 4);
  EXPECT_EQ(score.false_negatives, 2);
  EXPECT_EQ(score.false_positives, 2);
  EXPECT_EQ(score.true_negatives, 3);
  EXPECT_DOUBLE_EQ(*score.precision, 4.0 / 6.0);
  EXPECT_DOUBLE_EQ(*score.recall, 4.0 / 6.0);
  const DetectionScore always = score_detection(truth, std::vector<bool>(truth.size(), true));
  EXPECT_DOUBLE_EQ(*always.precision, 6.0 / 11.0);
  EXPECT_DOUBLE_EQ(*always.recall, 1.0);
}

TEST(DegenerationDetection, UndefinedRatiosAreEmpty) {
  const DetectionScore never = score_detection({0, 0, 1}, {0, 0, 0});
  EXPECT_FALSE(never.precision);
  EXPECT_DOUBLE_EQ(*never.recall, 0.0);
  const DetectionScore no_truth = score_detection({0, 0}, {1, 0});
  EXPECT_DOUBLE_EQ(*no_truth.precision, 0.0);
  EXPECT_FALSE(no_truth.recall);
  EXPECT_THROW(score_detection({0, 1}, {0}), std::invalid_argument);
}
