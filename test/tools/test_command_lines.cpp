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
