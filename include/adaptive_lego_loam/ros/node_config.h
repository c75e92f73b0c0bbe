#pragma once
// What every node reads from its private namespace at start-up: the sensor config (~config, a
// YAML path; else ~sensor, the name of one of the package's config/*.yaml), the frame names,
// and the shared start-up of main().

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/workers.h"

namespace adaptive_lego_loam::ros_bridge {

// The package's config directory: the source tree's config/ this library was built from while it
// exists, else roslib's (an installed package).
std::string package_config_dir();

// ~config when set and not empty, else <config dir>/<~sensor>.yaml (~sensor defaults to vlp16).
// Throws ConfigError naming the parameter and the known sensors when there is no such file.
std::string config_path(const ros::NodeHandle& private_nh);
// The same split at spaces: ~config may name several files, each later one's keys replacing the
// earlier ones' (a sensor's config, then a robot's extrinsics and IMU), as run_sequence --config.
std::vector<std::string> config_paths(const ros::NodeHandle& private_nh);

// load_config(config_paths(private_nh)): throws ConfigError naming the file, key and range.
Config load_node_config(const ros::NodeHandle& private_nh);

struct FrameNames {
  std::string map = "map";
  std::string odom = "odom";
  std::string base;  // empty: the sensor frame is the robot's base (no base_link -> sensor TF)
  std::string sensor = "velodyne";  // used only for clouds whose header has no frame_id
};
// ~map_frame, ~odom_frame, ~base_frame, ~sensor_frame.
FrameNames load_frame_names(const ros::NodeHandle& private_nh);

// ~threads (default 1): the threads a stage shares its per-point searches among (nullptr: the
// node's own thread alone). Throws ConfigError naming the parameter outside 1-64.
std::unique_ptr<Workers> load_workers(const ros::NodeHandle& private_nh);

// Set by SIGINT and SIGTERM in a node's process (run_node).
void request_node_stop(int signal);
bool node_stop_requested();

// main() of every node: ros::init, the node object built from the config, callbacks until
// Ctrl-C (SIGINT) or SIGTERM. A bad config or any other start-up error stops the node with exit
// status 1 and a FATAL line that holds the loader's message. The node object is destroyed before
// ROS shuts down, so that what it logs on exit (its summary, the map saved on exit) is written:
// roscpp's own SIGINT handler would shut the logging down first.
template <typename Node>
int run_node(int argc, char** argv, const std::string& name) {
  // Each log line out at once when stdout is a file or a pipe (roslaunch piped to tee, a
  // service's journal), not in blocks that a node stopped by a signal never writes.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  ros::init(argc, argv, name, ros::init_options::NoSigintHandler);
  std::signal(SIGINT, request_node_stop);
  std::signal(SIGTERM, request_node_stop);
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  std::unique_ptr<Node> node;
  try {
    node = std::make_unique<Node>(nh, private_nh, load_node_config(private_nh));
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", ros::this_node::getName().c_str(), e.what());
    return 1;
  }
  while (ros::ok() && !node_stop_requested())
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.1));
  node.reset();
  ros::shutdown();
  return 0;
}

}  // namespace adaptive_lego_loam::ros_bridge
