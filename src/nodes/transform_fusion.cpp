// transform_fusion: the scan-to-scan odometry at its full rate, corrected by the latest
// scan-to-map result (LeGO-LOAM's transformFusion), and the odom -> base TF of REP-105.
//
// TF chain: map -> odom (map_optimization: the mapping correction) -> base (this node: the
// odometry pose) [-> sensor (static, from the robot description, when base is not the sensor)].

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <optional>

#include "adaptive_lego_loam/core/mapping/transform_fusion.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_logging.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/stamp_matcher.h"

using namespace adaptive_lego_loam;

namespace {

enum Slot : std::size_t { kOdometry, kMapped };

class TransformFusionNode {
 public:
  TransformFusionNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config&)
      : frames_(ros_bridge::load_frame_names(private_nh)),
        pairing_("transform_fusion", {"laser_odom_to_init", "aft_mapped_to_init"},
                 private_nh.param("max_pending_scans", 50),
                 private_nh.param("warning_period", 5.0)),
        warn_("transform_fusion", private_nh.param("warning_period", 5.0)) {
    const int queue = private_nh.param("queue_size", 5);
    integrated_pub_ = nh.advertise<nav_msgs::Odometry>("integrated_to_init", queue);
    odometry_sub_ =
        nh.subscribe("laser_odom_to_init", queue, &TransformFusionNode::on_odometry, this);
    mapped_sub_ = nh.subscribe("aft_mapped_to_init", queue, &TransformFusionNode::on_mapped, this);
    if (!frames_.base.empty()) tf_listener_.emplace(tf_buffer_);
  }

 private:
  void on_odometry(const nav_msgs::OdometryConstPtr& msg) {
    Eigen::Isometry3d odometry_pose;
    try {
      odometry_pose = ros_bridge::pose_from_ros(msg->pose.pose, odometry_sub_.getTopic());
    } catch (const std::exception& e) {
      warn_(e.what());
      return;
    }
    add(kOdometry, msg->header, msg);
    std_msgs::Header map_header = msg->header;
    map_header.frame_id = frames_.map;
    integrated_pub_.publish(
        ros_bridge::odometry_to_ros(fusion_.fuse(odometry_pose), map_header, msg->child_frame_id));
    publish_odom_to_base(odometry_pose, *msg);
  }

  void on_mapped(const nav_msgs::OdometryConstPtr& msg) { add(kMapped, msg->header, msg); }

  void add(Slot slot, const std_msgs::Header& header, ros_bridge::StampMatcher::Message msg) {
    const auto group = pairing_.add(slot, header.stamp, std::move(msg));
    if (!group) return;
    try {
      fusion_.update_mapping(
          ros_bridge::pose_from_ros(group->get<nav_msgs::Odometry>(kOdometry)->pose.pose,
                                    odometry_sub_.getTopic()),
          ros_bridge::pose_from_ros(group->get<nav_msgs::Odometry>(kMapped)->pose.pose,
                                    mapped_sub_.getTopic()));
    } catch (const std::exception& e) {
      warn_(e.what());
    }
  }

  // odom -> base: the sensor's odometry pose, moved to the base frame when there is one.
  void publish_odom_to_base(const Eigen::Isometry3d& odometry_pose, const nav_msgs::Odometry& msg) {
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

  // The sensor's pose in the base frame (static, from TF), looked up once.
  std::optional<Eigen::Isometry3d> mounting(const std::string& sensor) {
    if (sensor_in_base_) return sensor_in_base_;
    try {
      sensor_in_base_ =
          tf2::transformToEigen(tf_buffer_.lookupTransform(frames_.base, sensor, ros::Time(0)));
    } catch (const tf2::TransformException& e) {
      warn_("no " + frames_.base + " -> " + sensor + " transform yet: " + e.what());
    }
    return sensor_in_base_;
  }

  ros_bridge::FrameNames frames_;
  TransformFusion fusion_;
  ros_bridge::ScanPairing pairing_;
  ros_bridge::ThrottledWarning warn_;
  ros::Subscriber odometry_sub_, mapped_sub_;
  ros::Publisher integrated_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::Buffer tf_buffer_;
  std::optional<tf2_ros::TransformListener> tf_listener_;
  std::optional<Eigen::Isometry3d> sensor_in_base_;
};

}  // namespace

int main(int argc, char** argv) {
  return ros_bridge::run_node<TransformFusionNode>(argc, argv, "transform_fusion");
}
