#include "transform_fusion.h"
#include "node_entry_points.h"

#include <tf2_eigen/tf2_eigen.h>

#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/shared_publish.h"

namespace adaptive_lego_loam::nodes {

TransformFusionNode::TransformFusionNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh,
                                         const Config& config)
    : frames_(ros_bridge::load_frame_names(private_nh)),
      pairing_("transform_fusion", {"laser_odom_to_init", "aft_mapped_to_init"},
               private_nh.param("max_pending_scans", 50), private_nh.param("warning_period", 5.0)),
      warn_("transform_fusion", private_nh.param("warning_period", 5.0)),
      diagnostics_(nh, private_nh, "transform_fusion", config.sensor.name,
                   config.sensor.scan_period) {
  const int queue = private_nh.param("queue_size", 5);
  integrated_pub_ = nh.advertise<nav_msgs::Odometry>("integrated_to_init", queue);
  odometry_sub_ =
      nh.subscribe("laser_odom_to_init", queue, &TransformFusionNode::on_odometry, this);
  mapped_sub_ = nh.subscribe("aft_mapped_to_init", queue, &TransformFusionNode::on_mapped, this);
  if (!frames_.base.empty())
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(tf_buffer_);
}

void TransformFusionNode::on_odometry(const nav_msgs::OdometryConstPtr& msg) {
  const StampStep step = diagnostics_.received(msg->header.stamp);
  if (step == StampStep::kBackward) {
    ROS_WARN("transform_fusion: time went back to %.3f s (a bag played again?): fusion reset",
             msg->header.stamp.toSec());
    fusion_ = TransformFusion();
  }
  Eigen::Isometry3d odometry_pose;
  Matrix6d odometry_covariance;
  try {
    odometry_pose = ros_bridge::pose_from_ros(msg->pose.pose, odometry_sub_.getTopic());
    odometry_covariance = ros_bridge::pose_covariance_from_ros(msg->pose, odometry_sub_.getTopic());
  } catch (const std::exception& e) {
    diagnostics_.dropped("bad pose");
    warn_(e.what());
    return;
  }
  add(kOdometry, msg->header, msg);
  std_msgs::Header map_header = msg->header;
  map_header.frame_id = frames_.map;
  nav_msgs::Odometry integrated =
      ros_bridge::odometry_to_ros(fusion_.fuse(odometry_pose), map_header, msg->child_frame_id);
  ros_bridge::set_pose_covariance(fusion_.fused_covariance(odometry_pose, odometry_covariance),
                                  integrated.pose);
  ros_bridge::publish_shared(integrated_pub_, std::move(integrated));
  publish_odom_to_base(odometry_pose, *msg);
  diagnostics_.processed(StageTimes());
}

void TransformFusionNode::add(Slot slot, const std_msgs::Header& header,
                              ros_bridge::StampMatcher::Message msg) {
  const auto group = pairing_.add(slot, header.stamp, std::move(msg));
  if (!group) return;
  try {
    const nav_msgs::Odometry& odometry = *group->get<nav_msgs::Odometry>(kOdometry);
    const nav_msgs::Odometry& mapped = *group->get<nav_msgs::Odometry>(kMapped);
    fusion_.update_mapping(
        ros_bridge::pose_from_ros(odometry.pose.pose, odometry_sub_.getTopic()),
        ros_bridge::pose_covariance_from_ros(odometry.pose, odometry_sub_.getTopic()),
        ros_bridge::pose_from_ros(mapped.pose.pose, mapped_sub_.getTopic()),
        ros_bridge::pose_covariance_from_ros(mapped.pose, mapped_sub_.getTopic()));
  } catch (const std::exception& e) {
    warn_(e.what());
  }
}

void TransformFusionNode::publish_odom_to_base(const Eigen::Isometry3d& odometry_pose,
                                               const nav_msgs::Odometry& msg) {
  const std::string& sensor = msg.child_frame_id.empty() ? frames_.sensor : msg.child_frame_id;
  std_msgs::Header header = msg.header;
  header.frame_id = frames_.odom;
  if (frames_.base.empty() || frames_.base == sensor) {
    tf_broadcaster_.sendTransform(ros_bridge::transform_to_ros(odometry_pose, header, sensor));
    return;
  }
  const std::optional<Eigen::Isometry3d> sensor_in_base = mounting(sensor);
  if (!sensor_in_base) return;
  tf_broadcaster_.sendTransform(ros_bridge::transform_to_ros(
      odometry_pose * sensor_in_base->inverse(), header, frames_.base));
}

std::optional<Eigen::Isometry3d> TransformFusionNode::mounting(const std::string& sensor) {
  if (sensor_in_base_) return sensor_in_base_;
  try {
    sensor_in_base_ =
        tf2::transformToEigen(tf_buffer_.lookupTransform(frames_.base, sensor, ros::Time(0)));
  } catch (const tf2::TransformException& e) {
    warn_("no " + frames_.base + " -> " + sensor + " transform yet: " + e.what());
  }
  return sensor_in_base_;
}

int run_transform_fusion(int argc, char** argv) {
  return ros_bridge::run_node<TransformFusionNode>(argc, argv, "transform_fusion");
}

}  // namespace adaptive_lego_loam::nodes
