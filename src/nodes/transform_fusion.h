#pragma once
// transform_fusion: the scan-to-scan odometry at its full rate, corrected by the latest
// scan-to-map result (LeGO-LOAM's transformFusion), and the odom -> base TF of REP-105.
//
// TF chain: map -> odom (map_optimization: the mapping correction) -> base (this node: the
// odometry pose) [-> sensor (static, from the robot description, when base is not the sensor)].

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <memory>
#include <optional>

#include "adaptive_lego_loam/core/mapping/transform_fusion.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_diagnostics.h"
#include "adaptive_lego_loam/ros/node_logging.h"
#include "adaptive_lego_loam/ros/stamp_matcher.h"

namespace adaptive_lego_loam::nodes {

class TransformFusionNode {
 public:
  TransformFusionNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config& config);

 private:
  enum Slot : std::size_t { kOdometry, kMapped };

  void on_odometry(const nav_msgs::OdometryConstPtr& msg);
  void on_mapped(const nav_msgs::OdometryConstPtr& msg) { add(kMapped, msg->header, msg); }
  void add(Slot slot, const std_msgs::Header& header, ros_bridge::StampMatcher::Message msg);
  // odom -> base: the sensor's odometry pose, moved to the base frame when there is one.
  void publish_odom_to_base(const Eigen::Isometry3d& odometry_pose, const nav_msgs::Odometry& msg);
  // The sensor's pose in the base frame (static, from TF), looked up once.
  std::optional<Eigen::Isometry3d> mounting(const std::string& sensor);

  ros_bridge::FrameNames frames_;
  TransformFusion fusion_;
  ros_bridge::ScanPairing pairing_;
  ros_bridge::ThrottledWarning warn_;
  ros::Subscriber odometry_sub_, mapped_sub_;
  ros::Publisher integrated_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;  // only with a base frame
  std::optional<Eigen::Isometry3d> sensor_in_base_;
  ros_bridge::NodeDiagnostics diagnostics_;
};

}  // namespace adaptive_lego_loam::nodes
