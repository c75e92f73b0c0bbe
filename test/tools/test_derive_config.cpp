// derive_config: a config measured from KITTI's scans that loads and reads them, and a clear "not
// a spinning LiDAR" for a solid-state cloud, leaving an earlier config as it was.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/core/common/params.h"
#include "support/run_command.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using adaptive_lego_loam::test::run_command;
using adaptive_lego_loam::test::temp_path;
namespace fs = std::filesystem;

namespace {

std::string derive_config(const std::string& arguments) {
  return std::string(BIN_DIR) + "/derive_config " + arguments;
}

std::string read_file(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

TEST(DeriveConfig, KittisScansGiveAConfigThatLoadsAndReadsThem) {
  const std::string output = temp_path("kitti_derived.yaml");
  const std::string input = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  const auto [status, report] =
      run_command(derive_config("--input " + input + " --output " + output));
  ASSERT_EQ(status, 0) << report;
  EXPECT_NE(report.find("64 rows from the order of the points"), std::string::npos) << report;
  const Config config = load_config(output);
  EXPECT_EQ(config.sensor.rows, 64);
  EXPECT_EQ(config.sensor.name, "kitti_derived");
  EXPECT_EQ(config.sensor.beam_offsets_m.size(), 64u);
  const std::string text = read_file(output);
  EXPECT_EQ(text.rfind("# Derived by derive_config from KITTI sequence", 0), 0u) << text;
  EXPECT_NE(text.find("stages' parameters are hdl64e.yaml's"), std::string::npos);
  // The measured config reads the scans it came from without a word from the fit check.
  const std::string run = temp_path("kitti_derived_run");
  const auto [run_status, run_output] =
      run_command(std::string(BIN_DIR) + "/run_sequence --config " + output + " --input " + input +
                  " --output " + run);
  EXPECT_EQ(run_status, 0) << run_output;
  EXPECT_EQ(run_output.find("does not fit"), std::string::npos) << run_output;
}

TEST(DeriveConfig, ASolidStateCloudIsNotASpinningLidarAndTheEarlierConfigStays) {
  const fs::path folder = temp_path("solid_state");
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream pcd(folder / "0.pcd");
  pcd << "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4000\nDATA ascii\n";
  for (int i = 0; i < 4000; ++i) {  // 60 deg of azimuth, 20 deg of elevation, 15 m away
    const double a = (-30.0 + 60.0 * (i % 100) / 100) * M_PI / 180.0;
    const double e = (-10.0 + 0.5 * (i / 100)) * M_PI / 180.0;
    pcd << 15 * std::cos(e) * std::cos(a) << " " << 15 * std::cos(e) * std::sin(a) << " "
        << 15 * std::sin(e) << "\n";
  }
  pcd.close();
  const std::string output = temp_path("kept.yaml");
  std::ofstream(output) << "earlier\n";
  const auto [status, message] =
      run_command("(" + derive_config("--input " + folder.string() + " --output " + output) +
                  " 2>&1 >/dev/null)");
  EXPECT_EQ(status, 1);
  EXPECT_NE(message.find("derive_config: " + folder.string() +
                         ": not a spinning LiDAR: the "
                         "points cover 61 deg of azimuth"),  // 1-deg bins
            std::string::npos)
      << message;
  EXPECT_EQ(read_file(output), "earlier\n");
}
