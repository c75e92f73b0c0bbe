#include "adaptive_lego_loam/io/pose_files.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace {

// Rounding in text files (KITTI's ground truth has 7 significant digits) leaves R^T R within
// ~1e-6 of I; anything beyond this is not a rotation, e.g. columns in the wrong order.
constexpr double kOrthonormalTolerance = 1e-3;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw IoError(where + ": " + what);
}

std::string where(const std::string& path, int line_number) {
  return path + ":" + std::to_string(line_number);
}

// Calls `handle(line_number, text)` for every line of `input` that is not blank (nor a '#'
// comment when `comments` is set). Line numbers start at 1.
void for_each_line(std::istream& input, const std::string& source, bool comments,
                   const std::function<void(int, const std::string&)>& handle) {
  std::string text;
  for (int line_number = 1; std::getline(input, text); ++line_number) {
    const std::size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (comments && text[first] == '#') continue;
    handle(line_number, text);
  }
  if (input.bad()) throw IoError(source + ": read failed");
}

// `parse` on the file at `path`, or on `text` below: one parser for files and memory.
template <typename Parse>
auto parse_file(const std::string& path, Parse parse) {
  std::ifstream file(path);
  if (!file) throw IoError(path + ": cannot open");
  return parse(file, path);
}

template <typename Parse>
auto parse_text(const std::string& text, const std::string& source, Parse parse) {
  std::istringstream input(text);
  return parse(input, source);
}

std::vector<double> parse_numbers(const std::string& text, const std::string& place) {
  std::istringstream tokens(text);
  std::vector<double> numbers;
  std::string token;
  while (tokens >> token) {
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size()) {
      fail(place, "expected a number, found '" + token + "'");
    }
    if (!std::isfinite(value)) {
      fail(place,
           "number " + std::to_string(numbers.size() + 1) + " is not finite ('" + token + "')");
    }
    numbers.push_back(value);
  }
  return numbers;
}

void expect_count(const std::vector<double>& numbers, std::size_t expected,
                  const std::string& place, const std::string& hint = "") {
  if (numbers.size() == expected) return;
  fail(place, "expected " + std::to_string(expected) + " numbers, found " +
                  std::to_string(numbers.size()) + hint);
}

void check_rotation(const Eigen::Matrix3d& rotation, const std::string& place) {
  const double deviation =
      (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (deviation > kOrthonormalTolerance || rotation.determinant() < 0) {
    fail(place, "the 3x3 rotation block is not a rotation (max |R^T R - I| = " +
                    std::to_string(deviation) + ", det " + std::to_string(rotation.determinant()) +
                    ")");
  }
}

// 12 numbers: the 3x4 [R|t] row-major. R is kept as written (not re-orthonormalised) so that
// reading and writing a file changes nothing.
Eigen::Isometry3d pose_from_row_major(const double* values, const std::string& place) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col)
      pose.matrix()(row, col) = values[4 * row + col];
  }
  check_rotation(pose.linear(), place);
  return pose;
}

std::string format_number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

void write_lines(const std::string& path, const std::vector<std::vector<double>>& rows) {
  std::ofstream file(path, std::ios::trunc);
  if (!file) throw IoError(path + ": cannot open for writing");
  for (const std::vector<double>& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i)
      file << (i ? " " : "") << format_number(row[i]);
    file << '\n';
  }
  file.close();
  if (!file) throw IoError(path + ": write failed");
}

std::vector<Eigen::Isometry3d> kitti_poses_from(std::istream& input, const std::string& path) {
  std::vector<Eigen::Isometry3d> poses;
  for_each_line(input, path, false, [&](int line_number, const std::string& text) {
    const std::string place = where(path, line_number);
    const std::vector<double> numbers = parse_numbers(text, place);
    const std::string hint =
        numbers.size() == 8 ? " (8 numbers is a TUM line: timestamp tx ty tz qx qy qz qw)" : "";
    expect_count(numbers, 12, place, hint);
    poses.push_back(pose_from_row_major(numbers.data(), place));
  });
  return poses;
}

StampedPoses tum_poses_from(std::istream& input, const std::string& path) {
  StampedPoses stamped;
  for_each_line(input, path, true, [&](int line_number, const std::string& text) {
    const std::string place = where(path, line_number);
    const std::vector<double> numbers = parse_numbers(text, place);
    expect_count(numbers, 8, place, " (timestamp tx ty tz qx qy qz qw)");
    Eigen::Quaterniond rotation(numbers[7], numbers[4], numbers[5], numbers[6]);
    // Stable: the plain norm of a quaternion like (1e200, 0, 0, 0) overflows, and dividing by
    // it gives the zero quaternion, whose rotation matrix is the identity.
    if (rotation.coeffs().stableNorm() < 1e-9) fail(place, "quaternion (qx qy qz qw) is zero");
    rotation.coeffs().stableNormalize();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = rotation.toRotationMatrix();
    pose.translation() << numbers[1], numbers[2], numbers[3];
    stamped.times.push_back(numbers[0]);
    stamped.poses.push_back(pose);
  });
  return stamped;
}

Eigen::Isometry3d kitti_calib_tr_from(std::istream& input, const std::string& path) {
  Eigen::Isometry3d tr = Eigen::Isometry3d::Identity();
  int tr_line = 0;
  for_each_line(input, path, false, [&](int line_number, const std::string& text) {
    std::istringstream tokens(text);
    std::string key;
    tokens >> key;
    if (key != "Tr:") return;
    const std::string place = where(path, line_number);
    if (tr_line)
      fail(place, "second 'Tr:' line (the first is line " + std::to_string(tr_line) + ")");
    tr_line = line_number;
    const std::vector<double> numbers = parse_numbers(text.substr(text.find("Tr:") + 3), place);
    expect_count(numbers, 12, place, " after 'Tr:'");
    tr = pose_from_row_major(numbers.data(), place);
  });
  if (!tr_line) {
    throw IoError(path + ": no 'Tr:' line (12 numbers, the velodyne-to-camera transform)");
  }
  return tr;
}

std::vector<double> kitti_times_from(std::istream& input, const std::string& path) {
  std::vector<double> times;
  for_each_line(input, path, false, [&](int line_number, const std::string& text) {
    const std::string place = where(path, line_number);
    const std::vector<double> numbers = parse_numbers(text, place);
    if (numbers.size() != 1) {
      fail(place, "expected 1 number (a timestamp), found " + std::to_string(numbers.size()));
    }
    times.push_back(numbers[0]);
  });
  return times;
}

}  // namespace

void write_kitti_poses(const std::string& path, const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<std::vector<double>> rows;
  for (const Eigen::Isometry3d& pose : poses) {
    std::vector<double>& row = rows.emplace_back();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c)
        row.push_back(pose.matrix()(r, c));
    }
  }
  write_lines(path, rows);
}

void write_tum_poses(const std::string& path, const std::vector<double>& times,
                     const std::vector<Eigen::Isometry3d>& poses) {
  if (times.size() != poses.size()) {
    throw IoError(path + ": " + std::to_string(times.size()) + " timestamps for " +
                  std::to_string(poses.size()) + " poses");
  }
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Eigen::Quaterniond q(poses[i].linear());
    q.normalize();
    if (q.w() < 0) q.coeffs() *= -1;  // q and -q are the same rotation; pick one for determinism
    const Eigen::Vector3d& t = poses[i].translation();
    rows.push_back({times[i], t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()});
  }
  write_lines(path, rows);
}

std::vector<Eigen::Isometry3d> read_kitti_poses(const std::string& path) {
  return parse_file(path, kitti_poses_from);
}

std::vector<Eigen::Isometry3d> parse_kitti_poses(const std::string& text,
                                                 const std::string& source) {
  return parse_text(text, source, kitti_poses_from);
}

StampedPoses read_tum_poses(const std::string& path) {
  return parse_file(path, tum_poses_from);
}

StampedPoses parse_tum_poses(const std::string& text, const std::string& source) {
  return parse_text(text, source, tum_poses_from);
}

Eigen::Isometry3d read_kitti_calib_tr(const std::string& path) {
  return parse_file(path, kitti_calib_tr_from);
}

Eigen::Isometry3d parse_kitti_calib_tr(const std::string& text, const std::string& source) {
  return parse_text(text, source, kitti_calib_tr_from);
}

std::vector<double> read_kitti_times(const std::string& path) {
  return parse_file(path, kitti_times_from);
}

std::vector<double> parse_kitti_times(const std::string& text, const std::string& source) {
  return parse_text(text, source, kitti_times_from);
}

}  // namespace adaptive_lego_loam
