#pragma once
// Sequences of scans for the offline tools: a KITTI sequence folder (velodyne/*.bin, times.txt)
// or a folder of PCD files. Bags are read by the ROS layer (ros/bag_sequence.h) behind the same
// interface.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

class ScanSequence {
 public:
  virtual ~ScanSequence() = default;
  // The next scan, or nothing at the end. Throws IoError on a scan that cannot be read.
  virtual std::optional<Scan> next() = 0;
  // Number of scans, when known in advance (-1 otherwise).
  virtual int size() const = 0;
  virtual std::string describe() const = 0;
  // The stamp of the scan next() last tried, read or not (nothing before the first call).
  std::optional<double> last_stamp() const { return last_stamp_; }

 protected:
  std::optional<double> last_stamp_;
};

// Scan files of a folder, sorted by name; stamps from `stamps` (one per scan), else a scan period
// apart.
class FileSequence : public ScanSequence {
 public:
  FileSequence(std::vector<std::string> files, std::vector<double> stamps, std::string description,
               double scan_period);
  std::optional<Scan> next() override;
  int size() const override { return static_cast<int>(files_.size()); }
  std::string describe() const override { return description_; }

 private:
  std::vector<std::string> files_;
  std::vector<double> stamps_;
  std::string description_;
  double scan_period_;
  std::size_t position_ = 0;
};

// A KITTI sequence folder (with velodyne/ inside, or the velodyne folder itself) or a folder of
// PCD files; stamps from the sequence's times.txt, else `scan_period` apart. Throws IoError naming
// the path when it is neither.
std::unique_ptr<ScanSequence> open_folder_sequence(const std::string& path,
                                                   double scan_period = kReferenceScanPeriod);
// Whether open_folder_sequence(path) finds a times.txt for the scans' stamps.
bool folder_has_times(const std::string& path);

// The KITTI calib.txt beside a sequence folder's velodyne/, if there is one.
std::optional<std::string> kitti_calib_beside(const std::string& path);

}  // namespace adaptive_lego_loam
