#include "adaptive_lego_loam/ros/node_config.h"

#include <csignal>

#include <ros/package.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <vector>

namespace adaptive_lego_loam::ros_bridge {
namespace fs = std::filesystem;

std::string package_config_dir() {
  // The source tree's config/ while it exists (a workspace build): roslib only for an installed
  // package, as it prints an error when the package is not on ROS_PACKAGE_PATH.
  if (fs::is_directory(CONFIG_DIR)) return CONFIG_DIR;
  const std::string package = ros::package::getPath("adaptive_lego_loam");
  if (!package.empty() && fs::is_directory(fs::path(package) / "config")) {
    return (fs::path(package) / "config").string();
  }
  return CONFIG_DIR;
}

namespace {

std::vector<std::string> known_sensors(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

std::string config_path(const ros::NodeHandle& private_nh) {
  std::string path;
  if (private_nh.getParam("config", path) && !path.empty()) return path;
  std::string sensor = "vlp16";
  private_nh.getParam("sensor", sensor);
  const std::string dir = package_config_dir();
  const fs::path candidate = fs::path(dir) / (sensor + ".yaml");
  if (fs::is_regular_file(candidate)) return candidate.string();
  std::string known;
  for (const std::string& name : known_sensors(dir))
    known += (known.empty() ? "" : ", ") + name;
  throw ConfigError(private_nh.resolveName("sensor") + " = '" + sensor + "': no " +
                    candidate.string() + " (known sensors: " + known + "); or give a file in " +
                    private_nh.resolveName("config"));
}

std::vector<std::string> config_paths(const ros::NodeHandle& private_nh) {
  std::istringstream words(config_path(private_nh));
  std::vector<std::string> paths;
  for (std::string path; words >> path;)
    paths.push_back(path);
  return paths;
}

Config load_node_config(const ros::NodeHandle& private_nh) {
  const std::vector<std::string> paths = config_paths(private_nh);
  return paths.size() == 1 ? load_config(paths.front()) : load_config(paths);
}

std::unique_ptr<Workers> load_workers(const ros::NodeHandle& private_nh) {
  const int threads = private_nh.param("threads", 1);
  if (threads < 1 || threads > 64) {
    throw ConfigError(private_nh.resolveName("threads") + " = " + std::to_string(threads) +
                      ": expected 1 to 64");
  }
  return threads > 1 ? std::make_unique<Workers>(threads) : nullptr;
}

FrameNames load_frame_names(const ros::NodeHandle& private_nh) {
  FrameNames frames;
  private_nh.param("map_frame", frames.map, frames.map);
  private_nh.param("odom_frame", frames.odom, frames.odom);
  private_nh.param("base_frame", frames.base, frames.base);
  private_nh.param("sensor_frame", frames.sensor, frames.sensor);
  return frames;
}

namespace {
volatile std::sig_atomic_t stop_requested = 0;
}  // namespace

void request_node_stop(int) {
  stop_requested = 1;
}

bool node_stop_requested() {
  return stop_requested != 0;
}

}  // namespace adaptive_lego_loam::ros_bridge
