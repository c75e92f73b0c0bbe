#pragma once
// A KITTI odometry sequence as a bag, as a Velodyne driver would have recorded it: each scan as
// sensor_msgs/PointCloud2 with ring and time fields, and the ground truth as nav_msgs/Odometry.

#include <functional>
#include <string>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam::ros_bridge {

struct KittiBagOptions {
  std::string input;        // sequence folder (velodyne/*.bin, times.txt, calib.txt, poses.txt)
  std::string output;       // .bag file
  std::string config_path;  // sensor config giving the rings (config/kitti.yaml)
  std::string poses_path;   // ground truth; empty: <input>/poses.txt when it exists
  // KITTI's times.txt starts at 0, and a stamp of 0 means "no time" to ROS: stamps are this
  // plus times.txt.
  double start_time = 1.0;
  std::string cloud_topic = "/velodyne_points";
  std::string truth_topic = "/ground_truth";
  std::string sensor_frame = "velodyne";
  std::string truth_frame = "map";  // the first scan's lidar frame, as our map frame
};

struct KittiBagSummary {
  int scans = 0;
  long long points = 0;
  long long dropped_points = 0;  // outside the config's beams (no ring) or not finite
  bool ground_truth = false;
  std::string note;  // why no ground truth was written, when poses exist but cannot be used
};

// Gives every point of a scan its ring (the range-image row `projector` puts it in by its
// elevation) and its time in the sweep (from its azimuth, turning clockwise from the first
// point over `scan_period`), and drops the points outside the beams. Returns how many it
// dropped.
int add_ring_and_time(const RangeProjector& projector, double scan_period, Scan& scan);

// Throws IoError / ConfigError naming the file on bad input. `progress(done, total)` is called
// after each scan.
KittiBagSummary write_kitti_bag(const KittiBagOptions& options,
                                const std::function<void(int, int)>& progress = {});

}  // namespace adaptive_lego_loam::ros_bridge
