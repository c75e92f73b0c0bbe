// lidar_sim says which shipped configs read what it wrote: the ring-less scans of its folder and
// the bag's clouds with their ring field.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/run_command.h"
#include "support/temp_files.h"

using adaptive_lego_loam::test::run_command;
using adaptive_lego_loam::test::temp_path;

namespace {

std::string simulate(const std::string& sensor) {
  const std::string out = temp_path("sim_" + sensor);
  const auto [status, output] =
      run_command(std::string(BIN_DIR) + "/lidar_sim --scenario highway --sensor " + sensor +
                  " --frames 1 --overwrite --output " + out + " --bag " + out + ".bag");
  std::filesystem::remove_all(out);
  std::filesystem::remove(out + ".bag");
  EXPECT_EQ(status, 0) << output;
  return output;
}

}  // namespace

TEST(LidarSim, SaysWhichShippedConfigsReadWhatItWrote) {
  // KITTI's HDL-64E: its beams' origins make ring-less scans kitti.yaml's alone.
  const std::string hdl64e = simulate("hdl64e");
  EXPECT_NE(hdl64e.find("the scans in velodyne/ (no ring field) fit config/kitti.yaml\n"),
            std::string::npos)
      << hdl64e;
  EXPECT_NE(hdl64e.find("the bag's clouds (with a ring field) fit config/hdl64e.yaml, "
                        "config/kitti.yaml\n"),
            std::string::npos)
      << hdl64e;
  const std::string os1 = simulate("os1_64");
  EXPECT_NE(os1.find("(with a ring field) fit config/os1_64.yaml\n"), std::string::npos) << os1;
}
