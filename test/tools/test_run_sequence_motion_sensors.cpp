// run_sequence with the optional motion sensors: without samples it is LiDAR-only to the bit; bad
// samples are dropped, counted and said once, the run completes and its poses recover; a broken
// file stops the run with its name and line.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.h"
#include "support/temp_files.h"

using adaptive_lego_loam::test::run_command;
using adaptive_lego_loam::test::temp_path;
namespace fs = std::filesystem;

namespace {

const std::string kConfig = std::string(CONFIG_DIR) + "/vlp16.yaml";

std::string read_file(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// A short simulated VLP-16 drive with its IMU and wheel odometry (and the faults asked for).
fs::path drive(const std::string& name, const std::string& faults = "") {
  const fs::path dir = temp_path(name);
  const std::string command = std::string(BIN_DIR) +
                              "/lidar_sim --scenario urban --sensor vlp16 --frames 80 --seed 3 "
                              "--imu --wheel-odom --overwrite --output " +
                              dir.string() + (faults.empty() ? "" : " --sensor-faults " + faults);
  const auto [status, output] = run_command(command);
  EXPECT_EQ(status, 0) << output;
  return dir;
}

std::pair<int, std::string> run_sequence(const fs::path& input, const fs::path& out,
                                         const std::string& sensors) {
  fs::remove_all(out);
  return run_command(std::string(BIN_DIR) + "/run_sequence --config " + kConfig + " --config " +
                     (input / "sensors.yaml").string() + " --input " + input.string() +
                     " --output " + out.string() + " " + sensors);
}

std::vector<Eigen::Vector3d> positions(const fs::path& poses) {
  std::vector<Eigen::Vector3d> out;
  std::ifstream file(poses);
  double m[12];
  while (file >> m[0]) {
    for (int i = 1; i < 12; ++i)
      file >> m[i];
    out.emplace_back(m[3], m[7], m[11]);
  }
  return out;
}

}  // namespace

TEST(RunSequenceMotionSensors, AnInputWithoutSamplesLeavesTheRunLidarOnly) {
  const fs::path input = drive("ms_drive");
  const auto [status, output] = run_sequence(input, temp_path("ms_lidar"), "");
  ASSERT_EQ(status, 0) << output;
  const fs::path empty = temp_path("ms_empty_imu.csv");
  std::ofstream(empty) << "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
  const auto [empty_status, empty_output] =
      run_sequence(input, temp_path("ms_empty"), "--imu " + empty.string());
  ASSERT_EQ(empty_status, 0) << empty_output;
  EXPECT_EQ(read_file(fs::path(temp_path("ms_empty")) / "poses_kitti.txt"),
            read_file(fs::path(temp_path("ms_lidar")) / "poses_kitti.txt"));
  const nlohmann::json summary =
      nlohmann::json::parse(read_file(fs::path(temp_path("ms_lidar")) / "summary.json"));
  EXPECT_FALSE(summary.contains("motion_sensors"));
}

TEST(RunSequenceMotionSensors, BadSamplesAreSaidOnceCountedAndThePosesRecover) {
  const fs::path faulty = drive(
      "ms_faulty", "imu:nan@1.0,imu:disorder@1.5,imu:repeat@1.7,imu:gap@2.0,wheel:absurd@1.2");
  auto sensors = [](const fs::path& d) {
    return "--imu " + (d / "imu.csv").string() + " --wheel-odom " + (d / "wheel_odom.csv").string();
  };
  const auto [status, output] = run_sequence(faulty, temp_path("ms_faulty_out"), sensors(faulty));
  ASSERT_EQ(status, 0) << output;
  for (const char* said : {"IMU sample at", "not finite", "out of order", "repeated stamp",
                           "wheel odometry sample at", "beyond limits"})
    EXPECT_NE(output.find(said), std::string::npos) << said << "\n" << output;
  const nlohmann::json summary =
      nlohmann::json::parse(read_file(fs::path(temp_path("ms_faulty_out")) / "summary.json"));
  const nlohmann::json& imu = summary["motion_sensors"]["imu"];
  EXPECT_EQ(imu["faults"]["not finite"], 1);
  EXPECT_GE(imu["faults"]["out of order"].get<int>(), 1);
  EXPECT_EQ(imu["faults"]["repeated stamp"], 1);
  EXPECT_EQ(imu["gaps"], 1);
  EXPECT_GE(imu["scans_lidar_only"].get<int>(), 1);
  EXPECT_EQ(summary["motion_sensors"]["wheel_odometry"]["faults"]["beyond limits"], 1);
  // After the gap the IMU is used again, and the drive ends no further from the truth than the
  // LiDAR alone takes it.
  EXPECT_GE(imu["restarts"].get<int>(), 1);
  const auto [lidar_status, lidar_output] = run_sequence(faulty, temp_path("ms_faulty_lidar"), "");
  ASSERT_EQ(lidar_status, 0) << lidar_output;
  const Eigen::Vector3d truth = positions(faulty / "poses.txt").back();
  const double lidar_error =
      (positions(fs::path(temp_path("ms_faulty_lidar")) / "poses_kitti.txt").back() - truth).norm();
  const double faulty_error =
      (positions(fs::path(temp_path("ms_faulty_out")) / "poses_kitti.txt").back() - truth).norm();
  EXPECT_LT(faulty_error, 1.5 * lidar_error + 0.1) << "LiDAR alone " << lidar_error;
}

TEST(RunSequenceMotionSensors, ABrokenFileStopsTheRunNamingItsLine) {
  const fs::path input = drive("ms_broken_drive");
  const fs::path broken = temp_path("ms_broken.csv");
  std::ofstream(broken)
      << "time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n0,0,0,0,0,0,9.8\n1,2,3\n";
  const auto [status, output] =
      run_sequence(input, temp_path("ms_broken_out"), "--imu " + broken.string());
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find(broken.string() + ":3: expected 7 comma-separated numbers"),
            std::string::npos)
      << output;
}
