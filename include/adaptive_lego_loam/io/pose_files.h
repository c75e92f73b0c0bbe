#pragma once
// Trajectory files: KITTI poses (3x4 [R|t] row-major per line), TUM poses (timestamp tx ty tz qx
// qy qz qw per line), and KITTI's calib.txt (its Tr line) and times.txt.
//
// Readers throw IoError as "<path>:<line>: <what was expected>" and reject non-finite numbers and
// rotation blocks that are not orthonormal. Blank lines are skipped; TUM files may also hold
// '#' comment lines. Each reader has a parse_* twin that reads the file's text from memory,
// `source` naming it in messages. Writers print every number in its shortest form that reads back
// to the same double (std::to_chars), so a write-read round trip is exact and the output
// deterministic.

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace adaptive_lego_loam {

std::vector<Eigen::Isometry3d> read_kitti_poses(const std::string& path);
std::vector<Eigen::Isometry3d> parse_kitti_poses(const std::string& text,
                                                 const std::string& source);
void write_kitti_poses(const std::string& path, const std::vector<Eigen::Isometry3d>& poses);

struct StampedPoses {
  std::vector<double> times;  // seconds
  std::vector<Eigen::Isometry3d> poses;
};

// Quaternions are normalised on reading; a zero quaternion is an error.
StampedPoses read_tum_poses(const std::string& path);
StampedPoses parse_tum_poses(const std::string& text, const std::string& source);
// Writes the quaternion with qw >= 0. Throws IoError when times and poses differ in length.
void write_tum_poses(const std::string& path, const std::vector<double>& times,
                     const std::vector<Eigen::Isometry3d>& poses);

// The `Tr:` line of a KITTI odometry calib.txt: velodyne-to-camera (x_cam = Tr * x_velo).
// Other lines (P0: .. P3:) are ignored.
Eigen::Isometry3d read_kitti_calib_tr(const std::string& path);
Eigen::Isometry3d parse_kitti_calib_tr(const std::string& text, const std::string& source);

// KITTI times.txt: one timestamp (seconds) per line.
std::vector<double> read_kitti_times(const std::string& path);
std::vector<double> parse_kitti_times(const std::string& text, const std::string& source);

}  // namespace adaptive_lego_loam
