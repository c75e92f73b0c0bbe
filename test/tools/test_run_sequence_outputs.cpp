// run_sequence's outputs: a run that fails leaves an earlier run's files as they were; with
// --skip-bad-scans an unreadable scan is skipped and counted; threads change no pose; a map folder
// that cannot take the map stops the run before it starts; degeneration.csv holds what the
// degeneration is scored on.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "adaptive_lego_loam/eval/degeneration_file.h"
#include "adaptive_lego_loam/io/numeric_csv.h"
#include "support/run_command.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using adaptive_lego_loam::test::run_command;
using adaptive_lego_loam::test::temp_path;
namespace fs = std::filesystem;

namespace {

const std::string kConfig = std::string(CONFIG_DIR) + "/kitti.yaml";

std::string run_sequence(const std::string& arguments) {
  return std::string(BIN_DIR) + "/run_sequence --config " + kConfig + " " + arguments;
}

std::string read_file(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// A copy of KITTI 07 frames 0-4 whose scan `broken` is cut to 17 bytes (no whole point).
fs::path sequence_with_broken_scan(const std::string& name, int broken) {
  const fs::path dir = temp_path(name);
  fs::remove_all(dir);
  fs::copy(std::string(TEST_DATA_DIR) + "/kitti_seq07", dir, fs::copy_options::recursive);
  char file[32];
  std::snprintf(file, sizeof(file), "velodyne/%010d.bin", broken);
  fs::resize_file(dir / file, 17);
  return dir;
}

}  // namespace

TEST(RunSequenceOutputs, AFailedRunLeavesTheEarlierRunsFiles) {
  const fs::path out = temp_path("outputs_kept");
  fs::remove_all(out);
  const std::string input = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  const auto [good_status, good_output] =
      run_command(run_sequence("--input " + input + " --output " + out.string()));
  ASSERT_EQ(good_status, 0) << good_output;
  const std::string poses = read_file(out / "poses_kitti.txt");
  const std::string summary = read_file(out / "summary.json");
  ASSERT_FALSE(poses.empty());

  const fs::path broken = sequence_with_broken_scan("broken_seq", 3);
  // With threads the broken scan is read while an earlier one is processed: it stops the run
  // all the same.
  for (const std::string threads : {"1", "2"}) {
    SCOPED_TRACE(threads + " threads");
    const auto [status, output] = run_command(run_sequence(
        "--input " + broken.string() + " --output " + out.string() + " --threads " + threads));
    EXPECT_EQ(status, 1) << output;
    EXPECT_NE(output.find("0000000003.bin"), std::string::npos) << output;
    EXPECT_NE(output.find("after 3 frames"), std::string::npos) << output;
    EXPECT_NE(output.find("as they were"), std::string::npos) << output;
    EXPECT_EQ(read_file(out / "poses_kitti.txt"), poses);
    EXPECT_EQ(read_file(out / "summary.json"), summary);
    for (const auto& entry : fs::directory_iterator(out))
      EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos)
          << "a temporary left behind: " << entry.path();
  }
}

TEST(RunSequenceOutputs, ThreadsChangeNoByteOfThePoses) {
  const std::string input = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  std::string reference;
  for (const std::string threads : {"1", "2", "3"}) {
    SCOPED_TRACE(threads + " threads");
    const fs::path out = temp_path("outputs_threads_" + threads);
    fs::remove_all(out);
    const auto [status, output] = run_command(
        run_sequence("--input " + input + " --output " + out.string() + " --threads " + threads));
    ASSERT_EQ(status, 0) << output;
    const std::string poses = read_file(out / "poses_kitti.txt");
    if (reference.empty()) reference = poses;
    EXPECT_EQ(poses, reference);
    EXPECT_EQ(nlohmann::json::parse(read_file(out / "summary.json"))["threads"],
              std::stoi(threads));
  }
  const fs::path out = temp_path("outputs_threads_max");
  fs::remove_all(out);
  const auto [status, output] = run_command(run_sequence(
      "--input " + input + " --output " + out.string() + " --threads 2 --max-frames 3"));
  ASSERT_EQ(status, 0) << output;
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary["frames"], 3);
  EXPECT_EQ(reference.find(read_file(out / "poses_kitti.txt")), 0u)
      << "the first three poses of the whole run";
}

TEST(RunSequenceOutputs, SkipBadScansPredictsTheScanAndCountsIt) {
  const fs::path broken = sequence_with_broken_scan("skip_seq", 2);
  std::string one_thread_poses;
  for (const std::string threads : {"1", "2"}) {
    SCOPED_TRACE(threads + " threads");
    const fs::path out = temp_path("outputs_skip_" + threads);
    fs::remove_all(out);
    const auto [status, output] =
        run_command(run_sequence("--input " + broken.string() + " --output " + out.string() +
                                 " --skip-bad-scans --threads " + threads));
    ASSERT_EQ(status, 0) << output;
    EXPECT_NE(output.find("frame 2 skipped"), std::string::npos) << output;
    const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
    EXPECT_EQ(summary["skipped_scans"], 1);
    EXPECT_EQ(summary["frames"], 5);
    EXPECT_EQ(summary["input_stamps"]["missing_scans"], 0) << "the skipped scan keeps its stamp";
    const std::string text = read_file(out / "poses_kitti.txt");
    std::istringstream poses(text);
    int lines = 0;
    for (std::string line; std::getline(poses, line);)
      ++lines;
    EXPECT_EQ(lines, 5) << "one pose a frame, the skipped one predicted";
    if (one_thread_poses.empty()) one_thread_poses = text;
    EXPECT_EQ(text, one_thread_poses);
  }
}

TEST(RunSequenceOutputs, AMapFolderThatHoldsSomethingElseStopsTheRunFirst) {
  const fs::path folder = temp_path("not_a_map");
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / "notes.txt") << "keep me\n";
  const fs::path out = temp_path("outputs_map");
  fs::remove_all(out);
  const auto [status, output] =
      run_command(run_sequence("--input " + std::string(TEST_DATA_DIR) + "/kitti_seq07 --output " +
                               out.string() + " --save-map " + folder.string()));
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find(folder.string()), std::string::npos) << output;
  EXPECT_NE(output.find("no map.yaml"), std::string::npos) << output;
  EXPECT_EQ(read_file(folder / "notes.txt"), "keep me\n");
  EXPECT_FALSE(fs::exists(out / "poses_kitti.txt")) << "the run should not have started";
}

// A recording paused for three minutes between scans 2 and 3: the gap is counted (1 800 scans
// missing at 10 Hz) and, the scans being what they are, no pose changes.
TEST(RunSequenceOutputs, ATimeGapOfMinutesIsCountedAndChangesNoPose) {
  const std::string input = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  const fs::path paused = temp_path("paused_seq");
  fs::remove_all(paused);
  fs::copy(input, paused, fs::copy_options::recursive);
  std::istringstream times(read_file(paused / "times.txt"));
  std::ostringstream shifted;
  shifted.precision(12);
  int line = 0;
  for (double t; times >> t; ++line)
    shifted << (line >= 3 ? t + 180.0 : t) << "\n";
  std::ofstream(paused / "times.txt") << shifted.str();
  const fs::path plain = temp_path("outputs_plain"), gap = temp_path("outputs_gap");
  fs::remove_all(plain);
  fs::remove_all(gap);
  ASSERT_EQ(run_command(run_sequence("--input " + input + " --output " + plain.string())).first, 0);
  const auto [status, output] =
      run_command(run_sequence("--input " + paused.string() + " --output " + gap.string()));
  ASSERT_EQ(status, 0) << output;
  const nlohmann::json summary = nlohmann::json::parse(read_file(gap / "summary.json"));
  EXPECT_EQ(summary["input_stamps"]["gaps"], 1);
  EXPECT_EQ(summary["input_stamps"]["missing_scans"], 1800);
  EXPECT_EQ(read_file(gap / "poses_kitti.txt"), read_file(plain / "poses_kitti.txt"));
}

// A config that does not fit the scans is said, once, on stderr and in summary.json: KITTI's
// scans with config/hdl64e.yaml (KITTI's beams without their origins) run, but not silently.
TEST(RunSequenceOutputs, AConfigThatDoesNotFitTheScansIsSaid) {
  const std::string input = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  const fs::path out = temp_path("config_fit");
  fs::remove_all(out);
  const auto [status, output] =
      run_command(std::string(BIN_DIR) + "/run_sequence --config " + std::string(CONFIG_DIR) +
                  "/hdl64e.yaml --input " + input + " --output " + out.string());
  ASSERT_EQ(status, 0) << output;
  const std::string warning = "hdl64e.yaml does not fit the clouds of " + input;
  const std::size_t first = output.find(warning);
  EXPECT_NE(first, std::string::npos) << output;
  EXPECT_EQ(output.find(warning, first + 1), std::string::npos) << "warned more than once";
  EXPECT_NE(output.find("derive_config"), std::string::npos);
  const nlohmann::json summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_FALSE(summary["config_fit"].empty());

  const fs::path fitting = temp_path("config_fits");
  fs::remove_all(fitting);
  const auto [kitti_status, kitti_output] =
      run_command(run_sequence("--input " + input + " --output " + fitting.string()));
  ASSERT_EQ(kitti_status, 0) << kitti_output;
  EXPECT_EQ(kitti_output.find("does not fit"), std::string::npos) << kitti_output;
  EXPECT_TRUE(nlohmann::json::parse(read_file(fitting / "summary.json"))["config_fit"].empty());
}

// degeneration.csv ends with map_optimization's flag, whether the scan matched and the published
// covariance (what evaluate_odometry --degeneration scores): the flag is its sigma beyond the
// config's 0.1 m, the first scan (no map yet) unmatched, the covariance symmetric and positive;
// then the scan-to-scan registration's weakest direction (none before the second scan).
TEST(RunSequenceOutputs, DegenerationEndsWithTheFlagAndThePublishedCovariance) {
  const fs::path out = temp_path("outputs_degeneration");
  fs::remove_all(out);
  const std::string input = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  ASSERT_EQ(run_command(run_sequence("--input " + input + " --output " + out.string())).first, 0);
  const std::string path = (out / "degeneration.csv").string();
  const NumericCsv table = read_csv_with_header(path);
  const std::vector<std::string> flag(table.columns.end() - 43, table.columns.end() - 40);
  EXPECT_EQ(flag, (std::vector<std::string>{"lidar_weak_sigma_m", "degenerate", "matched"}));
  EXPECT_EQ(*(table.columns.end() - 5), "covariance_55");
  const std::vector<std::string> odometry(table.columns.end() - 4, table.columns.end());
  EXPECT_EQ(odometry, (std::vector<std::string>{"odometry_weak_sigma_m", "odometry_weak_x",
                                                "odometry_weak_y", "odometry_weak_z"}));
  const int odometry_sigma = table.column("odometry_weak_sigma_m");
  EXPECT_TRUE(std::isinf(table.rows[0][odometry_sigma]));
  const RunDegeneration run = read_degeneration_csv(path, 0.1);
  ASSERT_EQ(run.scans.size(), 5u);
  EXPECT_EQ(run.flag_source, FlagSource::kPublished);
  EXPECT_EQ(run.uncertainty_source, UncertaintySource::kCovariance);
  EXPECT_EQ(run.scans[0].matched, false);
  const int sigma = table.column("lidar_weak_sigma_m");
  for (std::size_t i = 1; i < run.scans.size(); ++i) {
    EXPECT_EQ(run.scans[i].matched, true) << i;
    EXPECT_EQ(run.scans[i].degenerate, table.rows[i][sigma] > 0.1) << i;
    EXPECT_LT(table.rows[i][odometry_sigma], 0.1) << "KITTI's street fixes the motion, " << i;
    const Eigen::Matrix3d& covariance = *run.scans[i].translation_covariance;
    EXPECT_TRUE(covariance.isApprox(covariance.transpose(), 1e-12)) << i;
    EXPECT_GT(covariance.llt().matrixL().toDenseMatrix().diagonal().minCoeff(), 0.0) << i;
  }
}
