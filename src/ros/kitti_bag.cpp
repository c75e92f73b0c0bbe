#include "adaptive_lego_loam/ros/kitti_bag.h"

#include <rosbag/bag.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "adaptive_lego_loam/core/odometry/deskew.h"
#include "adaptive_lego_loam/eval/metrics.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_sequence.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"

namespace adaptive_lego_loam::ros_bridge {
namespace fs = std::filesystem;

namespace {

// The lidar's ground-truth poses, one per scan, when the sequence has usable ones.
std::optional<std::vector<Eigen::Isometry3d>> lidar_ground_truth(const KittiBagOptions& options,
                                                                 int scans,
                                                                 KittiBagSummary& summary) {
  std::string poses_path = options.poses_path;
  if (poses_path.empty()) {
    const fs::path beside = fs::path(options.input) / "poses.txt";
    if (!fs::is_regular_file(beside)) return std::nullopt;
    poses_path = beside.string();
  }
  const std::optional<std::string> calib = kitti_calib_beside(options.input);
  if (!calib) {
    summary.note = poses_path +
                   " is in the camera frame and there is no calib.txt to turn it "
                   "into the lidar's: no ground truth written";
    return std::nullopt;
  }
  const std::vector<Eigen::Isometry3d> camera = read_kitti_poses(poses_path);
  if (static_cast<int>(camera.size()) < scans) {
    throw IoError(poses_path + ": " + std::to_string(camera.size()) + " poses for " +
                  std::to_string(scans) + " scans");
  }
  return camera_to_lidar_poses(camera, read_kitti_calib_tr(*calib));
}

}  // namespace

int add_ring_and_time(const RangeProjector& projector, double scan_period, Scan& scan) {
  std::vector<ScanPoint> kept;
  kept.reserve(scan.points.size());
  for (ScanPoint p : scan.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    p.ring = projector.row_from_elevation(p.x, p.y, p.z);
    if (p.ring >= 0) kept.push_back(p);
  }
  const int dropped = static_cast<int>(scan.points.size() - kept.size());
  scan.points = std::move(kept);
  if (!scan.points.empty()) {
    // The core's own azimuth fallback for de-skewing gives each point's place in the sweep.
    std::vector<float> fractions;
    const ScanPoint& first = scan.points.front();
    sweep_fractions(scan.points, false, std::atan2(first.y, first.x), scan_period, fractions);
    for (std::size_t i = 0; i < scan.points.size(); ++i)
      scan.points[i].time = static_cast<float>(fractions[i] * scan_period);
  }
  scan.has_ring = scan.has_time = true;
  return dropped;
}

KittiBagSummary write_kitti_bag(const KittiBagOptions& options,
                                const std::function<void(int, int)>& progress) {
  const Config config = load_config(options.config_path);
  const RangeProjector projector(config.sensor);
  std::unique_ptr<ScanSequence> sequence = open_folder_sequence(options.input);
  const int scans = sequence->size();
  KittiBagSummary summary;
  const auto truth = lidar_ground_truth(options, scans, summary);
  summary.ground_truth = truth.has_value();

  rosbag::Bag bag;
  try {
    bag.open(options.output, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    throw IoError(options.output + ": cannot write bag: " + e.what());
  }
  while (std::optional<Scan> scan = sequence->next()) {
    summary.points += static_cast<long long>(scan->points.size());
    summary.dropped_points += add_ring_and_time(projector, config.sensor.scan_period, *scan);
    std_msgs::Header header;
    header.seq = static_cast<uint32_t>(summary.scans);
    header.stamp.fromSec(options.start_time + scan->stamp);
    header.frame_id = options.sensor_frame;
    bag.write(options.cloud_topic, header.stamp, to_ros(scan->points, header, true));
    if (truth) {
      std_msgs::Header truth_header = header;
      truth_header.frame_id = options.truth_frame;
      bag.write(options.truth_topic, header.stamp,
                odometry_to_ros((*truth)[summary.scans], truth_header, options.sensor_frame));
    }
    ++summary.scans;
    if (progress) progress(summary.scans, scans);
  }
  bag.close();
  return summary;
}

}  // namespace adaptive_lego_loam::ros_bridge
