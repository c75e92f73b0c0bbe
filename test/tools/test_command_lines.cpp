// Every command-line tool keeps the same contract: --help exits 0, a wrong command line exits 2
// and bad input exits 1, each with one line on stderr that names the tool.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/run_command.h"

using adaptive_lego_loam::test::run_command;

namespace {

const std::vector<std::string> kTools = {"run_sequence", "evaluate_odometry", "segmentation_bench",
                                         "lidar_sim",    "kitti_to_bag",      "segment_scans",
                                         "derive_config"};

std::string tool(const std::string& name) {
  return std::string(BIN_DIR) + "/" + name;
}

// The tool's stderr alone (its stdout thrown away) and its exit status.
std::pair<int, std::string> stderr_of(const std::string& command) {
  return run_command("(" + command + " 2>&1 >/dev/null)");
}

int lines_of(const std::string& text) {
  int lines = 0;
  for (char c : text)
    lines += c == '\n';
  return lines;
}

}  // namespace

TEST(CommandLines, HelpExitsZero) {
  for (const std::string& name : kTools) {
    const auto [status, output] = run_command(tool(name) + " --help");
    EXPECT_EQ(status, 0) << name;
    EXPECT_NE(output.find("Usage"), std::string::npos) << name << ": " << output;
  }
}

TEST(CommandLines, AWrongCommandLineExitsTwoWithOneLine) {
  for (const std::string& name : kTools) {
    const auto [status, output] = stderr_of(tool(name) + " --no-such-option");
    EXPECT_EQ(status, 2) << name << ": " << output;
    EXPECT_EQ(lines_of(output), 1) << name << ": " << output;
    EXPECT_EQ(output.rfind(name + ": ", 0), 0u) << output;
  }
}

TEST(CommandLines, BadInputExitsOneWithOneLineNamingTheFile) {
  const std::string missing = "/nonexistent/input";
  const std::string config = std::string(CONFIG_DIR) + "/vlp16.yaml";
  const std::vector<std::pair<std::string, std::string>> calls = {
      {"run_sequence", "--config " + config + " --input " + missing + " --output /tmp/alego_x"},
      {"evaluate_odometry", "--gt " + missing + " --est " + missing},
      {"segmentation_bench", "--points " + missing + " --labels " + missing + " --method all"},
      {"kitti_to_bag", "--input " + missing + " --output /tmp/alego_x.bag"},
      {"segment_scans", "--config " + config + " " + missing + "/scan.bin"},
      {"derive_config", "--input " + missing + ".bag --output /tmp/alego_x.yaml"},
      {"lidar_sim",
       "--scenario urban --sensor vlp16 --frames 2 --output /tmp/alego_sim "
       "--trajectory " +
           missing},
  };
  for (const auto& [name, arguments] : calls) {
    const auto [status, output] = stderr_of(tool(name) + " " + arguments);
    EXPECT_EQ(status, 1) << name << ": " << output;
    EXPECT_EQ(lines_of(output), 1) << name << ": " << output;
    EXPECT_EQ(output.rfind(name + ": ", 0), 0u) << output;
    EXPECT_NE(output.find(missing), std::string::npos) << name << ": " << output;
  }
}

// The motion sensors' options without a motion sensor, or a fault list that does not parse, are
// a wrong command line: lidar_sim says so before it builds a scene.
TEST(CommandLines, LidarSimMotionSensorOptionsAreChecked) {
  const std::string sim =
      tool("lidar_sim") + " --scenario urban --sensor vlp16 --frames 2 --output /tmp/alego_sim ";
  for (const std::string& arguments :
       {std::string("--imu-rate 100"), std::string("--imu --sensor-faults imu:melt@3"),
        std::string("--wheel-odom --motion-errors wheel-noise,bogus")}) {
    const auto [status, output] = stderr_of(sim + arguments);
    EXPECT_EQ(status, 2) << arguments << ": " << output;
    EXPECT_EQ(lines_of(output), 1) << output;
    EXPECT_EQ(output.rfind("lidar_sim: ", 0), 0u) << output;
  }
}

TEST(CommandLines, AnUnknownBaselineIsAUsageErrorNamingTheKnownOnes) {
  const std::string poses = std::string(TEST_DATA_DIR) + "/kitti_seq07/poses.txt";
  const std::string evaluate = tool("evaluate_odometry") + " --gt " + poses + " --est " + poses;
  for (const char* baseline : {"imu imu.csv", "constant-velocity extra.csv"}) {
    const auto [status, output] = stderr_of(evaluate + " --baseline " + std::string(baseline));
    EXPECT_EQ(status, 2) << baseline << ": " << output;
    EXPECT_EQ(lines_of(output), 1) << output;
    EXPECT_NE(output.find("constant-velocity"), std::string::npos) << output;
  }
  // The wheel baseline needs the scans' stamps, and its file must be there.
  const std::string times = std::string(TEST_DATA_DIR) + "/kitti_seq07/times.txt";
  const auto [no_times, no_times_output] = stderr_of(evaluate + " --baseline wheel odom.csv");
  EXPECT_EQ(no_times, 2) << no_times_output;
  EXPECT_NE(no_times_output.find("--times"), std::string::npos) << no_times_output;
  const auto [missing, missing_output] =
      stderr_of(evaluate + " --baseline wheel /nonexistent/odom.csv --times " + times);
  EXPECT_EQ(missing, 1) << missing_output;
  EXPECT_EQ(lines_of(missing_output), 1) << missing_output;
  EXPECT_NE(missing_output.find("/nonexistent/odom.csv"), std::string::npos) << missing_output;
  const auto [status, output] = run_command(evaluate + " --baseline constant-velocity");
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("reach ratio"), std::string::npos) << output;
}

// The degeneration's scoring takes both files; a bad one exits 1 with one line naming it.
TEST(CommandLines, EvaluateOdometryScoresTheDegenerationFromBothFilesOnly) {
  const std::string poses = std::string(TEST_DATA_DIR) + "/kitti_seq07/poses.txt";
  const std::string evaluate = tool("evaluate_odometry") + " --gt " + poses + " --est " + poses;
  const auto [alone, alone_output] = stderr_of(evaluate + " --observability obs.csv");
  EXPECT_EQ(alone, 2) << alone_output;
  EXPECT_NE(alone_output.find("--degeneration"), std::string::npos) << alone_output;
  // Not an observability.csv: the poses, space-separated.
  const auto [status, output] =
      stderr_of(evaluate + " --observability " + poses + " --degeneration /nonexistent/d.csv");
  EXPECT_EQ(status, 1) << output;
  EXPECT_EQ(lines_of(output), 1) << output;
  EXPECT_NE(output.find(poses + ":1: column 1: expected a number"), std::string::npos) << output;
}
