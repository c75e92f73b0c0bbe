#include <gtest/gtest.h>

#include <string>

#include "adaptive_lego_loam/eval/degeneration_file.h"
#include "adaptive_lego_loam/eval/observability_file.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using adaptive_lego_loam::test::error_of;

namespace {

// A line of observability.csv: the frame, then a diagonal information.
std::string observability_line(int frame, double diagonal) {
  std::string line = std::to_string(frame);
  for (int k = 0; k < 36; ++k)
    line += "," + std::to_string(k % 7 == 0 ? diagonal : 0.0);
  return line + "\n";
}

const char* const kOldHeader =
    "frame,mu,map_weak_sigma_m,map_weak_x,map_weak_y,map_weak_z,map_rotation_sigma_deg\n";

// A degeneration.csv header with the flag and covariance columns run_sequence writes now.
std::string new_header() {
  std::string header = "frame,map_weak_sigma_m,map_weak_x,map_weak_y,map_weak_z,degenerate,matched";
  for (int k = 0; k < 36; ++k)
    header += ",covariance_" + std::to_string(k / 6) + std::to_string(k % 6);
  return header + "\n";
}

// A row of it: the translation's variances 1, 4, 9 on the diagonal.
std::string new_row(int frame, int degenerate, int matched) {
  std::string row = std::to_string(frame) + ",0.05,1,0,0," + std::to_string(degenerate) + "," +
                    std::to_string(matched);
  for (int k = 0; k < 36; ++k) {
    const int r = k / 6, c = k % 6;
    row += "," + std::to_string(r == c ? (r < 3 ? 0.01 : (r - 2.0) * (r - 2.0)) : 0.0);
  }
  return row + "\n";
}

}  // namespace

TEST(ObservabilityFile, ReadsTheMatrixRowByRowAfterTheComments) {
  std::string text = "# comment\n# another\n" + observability_line(0, 2.0);
  text += "1";
  for (int k = 0; k < 36; ++k)
    text += "," + std::to_string(k);
  text += "\n";
  const std::vector<TrueObservability> scans = parse_observability_csv(text, "obs.csv");
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[0].frame, 0);
  const Eigen::Matrix<double, 6, 6> twice = 2.0 * Eigen::Matrix<double, 6, 6>::Identity();
  EXPECT_EQ(scans[0].information, twice);
  EXPECT_EQ(scans[1].frame, 1);
  EXPECT_EQ(scans[1].information(0, 5), 5.0);
  EXPECT_EQ(scans[1].information(5, 0), 30.0);
}

TEST(ObservabilityFile, BadLinesNameTheFileTheLineAndWhatWasExpected) {
  const std::string good = "# c\n" + observability_line(0, 1.0);
  EXPECT_EQ(error_of([] { parse_observability_csv("# only\n", "obs.csv"); }),
            "obs.csv: no scan: expected a line per scan (the scan index and the 36 entries of "
            "its information matrix)");
  EXPECT_EQ(error_of([&] { parse_observability_csv(good + "1,2,3\n", "obs.csv"); }),
            "obs.csv:3: expected 37 comma-separated numbers (the scan index and the 36 entries "
            "of its information matrix), found 3");
  EXPECT_EQ(error_of([&] { parse_observability_csv(good + observability_line(0, 1.0), "o"); }),
            "o:3: expected a scan index, an integer above 0, found 0.000000");
  std::string word = good + observability_line(1, 1.0);
  word.replace(word.rfind(",0.000000"), 9, ",x");
  EXPECT_EQ(error_of([&] { parse_observability_csv(word, "o"); }),
            "o:3: column 36: expected a number, found 'x'");  // entry I54
  std::string infinite = observability_line(1, 1.0);
  infinite.replace(infinite.find(",1.000000"), 9, ",inf");
  EXPECT_EQ(error_of([&] { parse_observability_csv(good + infinite, "o"); }),
            "o:3: column 2: expected a finite information entry");
  EXPECT_EQ(error_of([] { read_observability_csv("/nonexistent/observability.csv"); }),
            "/nonexistent/observability.csv: cannot open");
}

TEST(DegenerationFile, ANewRunGivesItsFlagAndTheTranslationBlockOfItsCovariance) {
  const RunDegeneration run =
      parse_degeneration_csv(new_header() + new_row(0, 1, 0) + new_row(1, 0, 1), "deg.csv", 0.1);
  EXPECT_EQ(run.flag_source, FlagSource::kPublished);
  EXPECT_EQ(run.uncertainty_source, UncertaintySource::kCovariance);
  ASSERT_EQ(run.scans.size(), 2u);
  EXPECT_TRUE(run.scans[0].degenerate);  // the column's, not map_weak_sigma_m's 0.05
  EXPECT_EQ(run.scans[0].matched, false);
  EXPECT_FALSE(run.scans[1].degenerate);
  EXPECT_EQ(run.scans[1].matched, true);
  ASSERT_TRUE(run.scans[1].translation_covariance);
  const Eigen::Matrix3d variances = Eigen::Vector3d(1.0, 4.0, 9.0).asDiagonal();
  EXPECT_EQ(*run.scans[1].translation_covariance, variances);
}

TEST(DegenerationFile, AnOldRunIsFlaggedByItsCorrespondencesSigmaBeyondTheThreshold) {
  const std::string text =
      std::string(kOldHeader) + "0,0.9,inf,0,0,1,inf\n1,0.9,0.2,1,0,0,1\n2,0.1,0.05,0,1,0,1\n";
  const RunDegeneration run = parse_degeneration_csv(text, "deg.csv", 0.1);
  EXPECT_EQ(run.flag_source, FlagSource::kCorrespondences);
  EXPECT_EQ(run.uncertainty_source, UncertaintySource::kCorrespondenceWeakest);
  ASSERT_EQ(run.scans.size(), 3u);
  EXPECT_TRUE(run.scans[0].degenerate);
  EXPECT_EQ(run.scans[0].matched, false);  // its correspondences fixed nothing
  EXPECT_TRUE(run.scans[1].degenerate);
  EXPECT_EQ(run.scans[1].matched, true);
  EXPECT_FALSE(run.scans[2].degenerate);
  EXPECT_FALSE(run.scans[2].translation_covariance);
  EXPECT_EQ(run.scans[1].weak_sigma_m, 0.2);
  EXPECT_EQ(run.scans[2].weak_direction, Eigen::Vector3d::UnitY());
  EXPECT_FALSE(parse_degeneration_csv(text, "deg.csv", 0.3).scans[1].degenerate);
  const std::string without_rotation =
      "frame,map_weak_sigma_m,map_weak_x,map_weak_y,map_weak_z\n0,inf,0,0,1\n";
  EXPECT_FALSE(parse_degeneration_csv(without_rotation, "d", 0.1).scans[0].matched);
}

TEST(DegenerationFile, BadInputNamesTheFileTheLineAndWhatWasExpected) {
  EXPECT_EQ(error_of([] { parse_degeneration_csv("frame,mu\n0,1\n", "d.csv", 0.1); }),
            "d.csv: expected a column map_weak_sigma_m in the header");
  EXPECT_EQ(error_of([] { parse_degeneration_csv("frame,map_weak_sigma_m\n0,1\n", "d", 0.1); }),
            "d: expected the columns covariance_00..covariance_55, estimate_weak_* or "
            "map_weak_* (sigma_m, x, y, z)");
  EXPECT_EQ(error_of([] { parse_degeneration_csv(std::string(kOldHeader) + "0,1\n", "d", 0.1); }),
            "d:2: expected 7 comma-separated numbers (one for each column of the header), "
            "found 2");
  EXPECT_EQ(error_of([] {
              parse_degeneration_csv(std::string(kOldHeader) + "0.5,1,1,1,0,0,1\n", "d", 0.1);
            }),
            "d:2: expected the frame, a non-negative integer");
  EXPECT_EQ(error_of([] {
              parse_degeneration_csv(std::string(kOldHeader) + "0,1,1,1,1,0,1\n", "d", 0.1);
            }),
            "d:2: expected a sigma and a unit weakest direction");
  EXPECT_EQ(error_of([] { parse_degeneration_csv(new_header() + new_row(0, 2, 1), "d", 0.1); }),
            "d:2: expected degenerate 0 or 1, found 2.000000");
  EXPECT_EQ(error_of([] { parse_degeneration_csv("", "d", 0.1); }),
            "d: empty: expected a header line of column names");
}
