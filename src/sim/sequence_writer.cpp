#include "adaptive_lego_loam/sim/sequence_writer.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/motion_sensor_files.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/sim/observability.h"

namespace adaptive_lego_loam::sim {
namespace fs = std::filesystem;
namespace {

const char* const kSequenceFiles[] = {"poses.txt",         "times.txt", "calib.txt",
                                      "observability.csv", "imu.csv",   "wheel_odom.csv",
                                      "sensors.yaml",      "scenario.yaml"};

std::string frame_name(int index, const char* extension) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d%s", index, extension);
  return name;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::trunc);
  file << text;
  if (!file) throw IoError(path.string() + ": write failed");
}

}  // namespace

SequenceWriter::SequenceWriter(std::string dir, bool overwrite, double range_noise_m)
    : dir_(std::move(dir)),
      range_noise_m_(range_noise_m),
      observability_(observability_header(range_noise_m)) {
  const fs::path root(dir_);
  std::error_code error;
  if (fs::exists(root / "velodyne", error)) {
    if (!overwrite) {
      throw IoError(dir_ +
                    ": already holds a sequence (velodyne/); choose another output folder "
                    "or pass --overwrite");
    }
    fs::remove_all(root / "velodyne", error);
    fs::remove_all(root / "labels", error);
    for (const char* name : kSequenceFiles)
      fs::remove(root / name, error);
  }
  fs::create_directories(root / "velodyne", error);
  fs::create_directories(root / "labels", error);
  if (error || !fs::is_directory(root / "labels")) {
    throw IoError(dir_ + ": cannot create the output folder" +
                  (error ? " (" + error.message() + ")" : std::string()));
  }
}

void SequenceWriter::write_frame(int index, const SimFrame& frame) {
  const fs::path root(dir_);
  write_kitti_bin((root / "velodyne" / frame_name(index, ".bin")).string(), frame.scan);
  write_labels((root / "labels" / frame_name(index, ".label")).string(), frame.labels);
  if (relative_poses_.empty()) first_pose_ = frame.sensor_pose;
  relative_poses_.push_back(first_pose_.inverse() * frame.sensor_pose);
  times_.push_back(frame.time);
  observability_ +=
      observability_line(index, scan_information(frame, observability_sigma(range_noise_m_)));
}

void SequenceWriter::finish(const std::string& scenario_yaml) {
  const fs::path root(dir_);
  std::string poses, times;
  for (const Eigen::Isometry3d& pose : relative_poses_)
    poses += kitti_pose_line(pose) + "\n";
  for (double time : times_) {
    char line[32];
    std::snprintf(line, sizeof(line), "%.6e\n", time);
    times += line;
  }
  write_text(root / "poses.txt", poses);
  write_text(root / "times.txt", times);
  const std::string identity = "1 0 0 0 0 1 0 0 0 0 1 0";
  std::string calib;
  for (const char* key : {"P0", "P1", "P2", "P3", "Tr"})
    calib += std::string(key) + ": " + identity + "\n";
  write_text(root / "calib.txt", calib);
  write_text(root / "observability.csv", observability_);
  write_text(root / "scenario.yaml", scenario_yaml);
}

void SequenceWriter::write_imu(const std::vector<ImuSample>& samples) {
  write_imu_csv((fs::path(dir_) / "imu.csv").string(), samples);
}

void SequenceWriter::write_wheel_odometry(const std::vector<WheelOdometrySample>& samples) {
  write_wheel_odometry_csv((fs::path(dir_) / "wheel_odom.csv").string(), samples);
}

void SequenceWriter::write_sensors_yaml(const std::string& text) {
  write_text(fs::path(dir_) / "sensors.yaml", text);
}

void write_labels(const std::string& path, const std::vector<uint32_t>& labels) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw IoError(path + ": cannot open for writing");
  // SemanticKITTI's files are little-endian, as is every machine this builds on.
  file.write(reinterpret_cast<const char*>(labels.data()),
             static_cast<std::streamsize>(labels.size() * sizeof(uint32_t)));
  if (!file) throw IoError(path + ": write failed");
}

std::vector<uint32_t> read_labels(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw IoError(path + ": cannot open label file");
  const std::streamsize bytes = file.tellg();
  if (bytes % 4 != 0) {
    throw IoError(path + ": size " + std::to_string(bytes) +
                  " bytes is not a multiple of 4 (one uint32 label per point)");
  }
  std::vector<uint32_t> labels(static_cast<std::size_t>(bytes / 4));
  file.seekg(0);
  if (!file.read(reinterpret_cast<char*>(labels.data()), bytes))
    throw IoError(path + ": read failed");
  return labels;
}

std::string kitti_pose_line(const Eigen::Isometry3d& pose) {
  std::string line;
  char number[32];
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 4; ++column) {
      std::snprintf(number, sizeof(number), "%.9e", pose.matrix()(row, column));
      line += (line.empty() ? "" : " ") + std::string(number);
    }
  }
  return line;
}

}  // namespace adaptive_lego_loam::sim
