#pragma once
// Writes a simulated sequence as a KITTI-style folder: velodyne/NNNNNN.bin, labels/NNNNNN.label
// (SemanticKITTI packing), poses.txt (sensor poses, first identity), times.txt, calib.txt
// (identity Tr: the poses are the LiDAR's), observability.csv (each scan's true information
// matrix, observability.h) and scenario.yaml.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"
#include "adaptive_lego_loam/sim/simulator.h"

namespace adaptive_lego_loam::sim {

class SequenceWriter {
 public:
  // Creates `dir` with velodyne/ and labels/. Throws IoError when `dir` already holds a sequence
  // (unless `overwrite`, which removes the files a sequence consists of) or cannot be written.
  // `range_noise_m`: the sensor's, the sigma of the scans' information.
  SequenceWriter(std::string dir, bool overwrite, double range_noise_m);

  void write_frame(int index, const SimFrame& frame);
  // Writes poses.txt (relative to the first frame's pose), times.txt, calib.txt,
  // observability.csv, scenario.yaml.
  void finish(const std::string& scenario_yaml);
  // The motion sensors' files, when they are simulated: imu.csv, wheel_odom.csv
  // (io/motion_sensor_files.h) and sensors.yaml (run_description.h's sensors_yaml).
  void write_imu(const std::vector<ImuSample>& samples);
  void write_wheel_odometry(const std::vector<WheelOdometrySample>& samples);
  void write_sensors_yaml(const std::string& text);

  // Sensor poses relative to the first frame, as written to poses.txt.
  const std::vector<Eigen::Isometry3d>& relative_poses() const { return relative_poses_; }

 private:
  std::string dir_;
  Eigen::Isometry3d first_pose_ = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Isometry3d> relative_poses_;
  std::vector<double> times_;
  double range_noise_m_;
  std::string observability_;
};

// One uint32 per point, little-endian, as SemanticKITTI's .label files.
void write_labels(const std::string& path, const std::vector<uint32_t>& labels);
std::vector<uint32_t> read_labels(const std::string& path);

// A pose as one KITTI line: the 3x4 matrix row by row.
std::string kitti_pose_line(const Eigen::Isometry3d& pose);

}  // namespace adaptive_lego_loam::sim
