// Writes a KITTI odometry sequence as a bag: /velodyne_points (PointCloud2 with ring and time
// fields) and, with poses.txt and calib.txt, the lidar's ground truth on /ground_truth.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

#include "adaptive_lego_loam/io/progress.h"
#include "adaptive_lego_loam/ros/kitti_bag.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;

int main(int argc, char** argv) {
  CLI::App app{
      "Write a KITTI odometry sequence (velodyne/*.bin, times.txt, and poses.txt + calib.txt "
      "when present) as a bag: /velodyne_points as sensor_msgs/PointCloud2 with ring (the "
      "range-image row of the config's beam table) and time (from the azimuth over the sweep) "
      "fields, and the lidar-frame ground truth as nav_msgs/Odometry on /ground_truth."};
  ros_bridge::KittiBagOptions options;
  options.config_path = ros_bridge::package_config_dir() + "/kitti.yaml";
  app.add_option("--input", options.input, "KITTI sequence folder")->required();
  app.add_option("--output", options.output, "bag to write")->required();
  app.add_option("--config", options.config_path, "sensor config giving the rings")
      ->capture_default_str();
  app.add_option("--poses", options.poses_path,
                 "ground-truth poses (KITTI format, camera frame; default: INPUT/poses.txt)");
  app.add_option("--start-time", options.start_time,
                 "stamp of times.txt's 0 (s); ROS reads a stamp of 0 as no time")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--frame", options.sensor_frame, "frame_id of the clouds")->capture_default_str();
  if (const auto status = tools::parse_command_line(app, argc, argv, "kitti_to_bag")) {
    return *status;
  }
  return tools::run_job("kitti_to_bag", [&] {
    std::unique_ptr<ProgressBar> progress;
    const ros_bridge::KittiBagSummary summary =
        ros_bridge::write_kitti_bag(options, [&progress](int done, int total) {
          if (!progress) progress = std::make_unique<ProgressBar>("kitti_to_bag", total);
          progress->update(done);
        });
    if (progress) progress->finish();
    if (!summary.note.empty()) std::fprintf(stderr, "kitti_to_bag: %s\n", summary.note.c_str());
    std::printf(
        "kitti_to_bag: %s: %d scans, %lld points (%lld outside the beams or not finite, "
        "left out), ground truth %s\n",
        options.output.c_str(), summary.scans, summary.points - summary.dropped_points,
        summary.dropped_points, summary.ground_truth ? "on /ground_truth" : "none");
    return tools::kExitOk;
  });
}
