#include "adaptive_lego_loam/io/scan_sequence.h"

#include <filesystem>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_files.h"

namespace adaptive_lego_loam {
namespace fs = std::filesystem;

FileSequence::FileSequence(std::vector<std::string> files, std::vector<double> stamps,
                           std::string description, double scan_period)
    : files_(std::move(files)),
      stamps_(std::move(stamps)),
      description_(std::move(description)),
      scan_period_(scan_period) {}

std::optional<Scan> FileSequence::next() {
  if (position_ >= files_.size()) return std::nullopt;
  // Moved on first: a scan that cannot be read is skipped when the caller goes on.
  const std::size_t index = position_++;
  last_stamp_ = index < stamps_.size() ? stamps_[index] : scan_period_ * index;
  // The sweep's period turns a legacy OS1's time (a share of the sweep) into seconds.
  Scan scan = read_scan_file(files_[index], {scan_period_});
  scan.stamp = *last_stamp_;
  return scan;
}

std::unique_ptr<ScanSequence> open_folder_sequence(const std::string& path, double scan_period) {
  if (!fs::is_directory(path)) throw IoError(path + ": not a directory");
  const fs::path velodyne = fs::path(path) / "velodyne";
  const fs::path folder = fs::is_directory(velodyne) ? velodyne : fs::path(path);
  std::vector<std::string> files = list_scan_files(folder.string());
  if (files.empty()) {
    throw IoError(path +
                  ": no .bin or .pcd scans (expected a KITTI sequence folder with "
                  "velodyne/*.bin, or a folder of .bin or .pcd files)");
  }
  std::vector<double> stamps;
  const fs::path times = folder.parent_path() / "times.txt";
  if (folder == velodyne && fs::is_regular_file(times)) {
    stamps = read_kitti_times(times.string());
    if (stamps.size() < files.size()) {
      throw IoError(times.string() + ": " + std::to_string(stamps.size()) + " stamps for " +
                    std::to_string(files.size()) + " scans");
    }
  }
  const std::string kind = folder == velodyne ? "KITTI sequence" : "scan folder";
  return std::make_unique<FileSequence>(
      std::move(files), std::move(stamps),
      kind + " " + path + " (" + std::to_string(files.size()) + " scans)", scan_period);
}

bool folder_has_times(const std::string& path) {
  const fs::path velodyne = fs::path(path) / "velodyne";
  return fs::is_directory(velodyne) && fs::is_regular_file(fs::path(path) / "times.txt");
}

std::optional<std::string> kitti_calib_beside(const std::string& path) {
  for (const fs::path& candidate :
       {fs::path(path) / "calib.txt", fs::path(path).parent_path() / "calib.txt"}) {
    if (fs::is_regular_file(candidate)) return candidate.string();
  }
  return std::nullopt;
}

}  // namespace adaptive_lego_loam
