// map_optimization: scan-to-map matching against the local map of keyframes (LeGO-LOAM's
// mapOptimization) on feature_association's features and odometry. Publishes the mapped pose,
// the map -> odom correction as TF, the keyframe positions, the path and the local map.

#include <adaptive_lego_loam/DegenerationState.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/transform_broadcaster.h>

#include "adaptive_lego_loam/core/pipeline/lidar_mapping.h"
#include "adaptive_lego_loam/ros/degeneration_conversions.h"
#include "adaptive_lego_loam/ros/feature_conversions.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_logging.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/stamp_matcher.h"

using namespace adaptive_lego_loam;

namespace {

enum Slot : std::size_t { kCorners, kSurfaces, kOutliers, kOdometry, kDegeneration };

std::vector<std::string> slot_names(bool with_degeneration) {
  std::vector<std::string> names = {"laser_cloud_corner_last", "laser_cloud_surf_last",
                                    "outlier_cloud_last", "laser_odom_to_init"};
  if (with_degeneration) names.push_back("degeneration");
  return names;
}

class MapOptimization {
 public:
  MapOptimization(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config& config)
      : params_(config.mapping),
        mapping_(config),
        uses_prior_(config.mapping.weak_direction_prior > 0.0),
        frames_(ros_bridge::load_frame_names(private_nh)),
        pairing_("map_optimization", slot_names(uses_prior_),
                 private_nh.param("max_pending_scans", 10),
                 private_nh.param("warning_period", 5.0)),
        surround_throttle_(private_nh.param("surround_period", 1.0)),
        warn_("map_optimization", private_nh.param("warning_period", 5.0)),
        summary_("map_optimization", private_nh.param("summary_period", 10.0)) {
    const int queue = private_nh.param("queue_size", 5);
    mapped_pub_ = nh.advertise<nav_msgs::Odometry>("aft_mapped_to_init", queue);
    surround_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_surround", 1);
    keyframe_pub_ = nh.advertise<sensor_msgs::PointCloud2>("key_pose_origin", 1);
    path_pub_ = nh.advertise<nav_msgs::Path>("path", 1);
    subscriptions_.push_back(
        nh.subscribe("laser_cloud_corner_last", queue, &MapOptimization::on_corners, this));
    subscriptions_.push_back(
        nh.subscribe("laser_cloud_surf_last", queue, &MapOptimization::on_surfaces, this));
    subscriptions_.push_back(
        nh.subscribe("outlier_cloud_last", queue, &MapOptimization::on_outliers, this));
    subscriptions_.push_back(
        nh.subscribe("laser_odom_to_init", queue, &MapOptimization::on_odometry, this));
    if (uses_prior_) {
      // image_projection is a whole stage ahead: a larger queue keeps its messages until the
      // features of the same scan arrive.
      subscriptions_.push_back(
          nh.subscribe("degeneration", 4 * queue, &MapOptimization::on_degeneration, this));
    }
  }

 private:
  void on_corners(const sensor_msgs::PointCloud2ConstPtr& msg) { add(kCorners, msg->header, msg); }
  void on_surfaces(const sensor_msgs::PointCloud2ConstPtr& msg) {
    add(kSurfaces, msg->header, msg);
  }
  void on_outliers(const sensor_msgs::PointCloud2ConstPtr& msg) {
    add(kOutliers, msg->header, msg);
  }
  void on_odometry(const nav_msgs::OdometryConstPtr& msg) { add(kOdometry, msg->header, msg); }
  void on_degeneration(const DegenerationStateConstPtr& msg) {
    add(kDegeneration, msg->header, msg);
  }

  void add(Slot slot, const std_msgs::Header& header, ros_bridge::StampMatcher::Message msg) {
    if (const auto group = pairing_.add(slot, header.stamp, std::move(msg))) process(*group);
  }

  void process(const ros_bridge::StampMatcher::Group& group) {
    const auto odometry = group.get<nav_msgs::Odometry>(kOdometry);
    try {
      const FeatureSet features = ros_bridge::mapping_features_from_ros(
          *group.get<sensor_msgs::PointCloud2>(kCorners),
          *group.get<sensor_msgs::PointCloud2>(kSurfaces),
          *group.get<sensor_msgs::PointCloud2>(kOutliers),
          {topic(kCorners), topic(kSurfaces), topic(kOutliers)});
      const Eigen::Isometry3d odometry_pose =
          ros_bridge::pose_from_ros(odometry->pose.pose, topic(kOdometry));
      std::optional<WeakDirectionPrior> prior;
      if (uses_prior_) {
        prior = ros_bridge::weak_direction_prior_from_ros(
            params_, *group.get<DegenerationState>(kDegeneration));
      }
      mapping_.process(features, odometry_pose, group.stamp.toSec(), prior, out_);
      sensor_frame_ = odometry->child_frame_id.empty() ? frames_.sensor : odometry->child_frame_id;
      stamps_.push_back(group.stamp);
      publish(group.stamp);
    } catch (const std::exception& e) {
      warn_(std::string("scan dropped: ") + e.what());
      return;
    }
    ROS_DEBUG("map_optimization: scan at %.3f: %s%s", group.stamp.toSec(),
              ros_bridge::format_stage_times(out_.times).c_str(),
              out_.keyframe ? " (keyframe)" : "");
    if (out_.loop) log_loop(*out_.loop);
    summary_.add(out_.times);
    if (const auto line = summary_.report()) ROS_INFO("%s", line->c_str());
  }

  std::string topic(Slot slot) const { return subscriptions_[slot].getTopic(); }

  // An attempt is reported on the scan it finished, some scans after its keyframe.
  static void log_loop(const LoopDetection& loop) {
    if (loop.accepted()) {
      ROS_INFO("map_optimization: loop closed: keyframe %d to %d (ICP fitness %.3f m^2)",
               loop.current_index, loop.matched_index, loop.fitness);
    } else {
      ROS_DEBUG("map_optimization: no loop at keyframe %d: %s (fitness %.3f m^2)",
                loop.current_index, to_string(loop.status), loop.fitness);
    }
  }

  void publish(const ros::Time& stamp) {
    std_msgs::Header map_header;
    map_header.stamp = stamp;
    map_header.frame_id = frames_.map;
    mapped_pub_.publish(ros_bridge::odometry_to_ros(out_.pose, map_header, sensor_frame_));
    tf_broadcaster_.sendTransform(
        ros_bridge::transform_to_ros(mapping_.fusion().correction(), map_header, frames_.odom));
    if (out_.keyframe && keyframe_pub_.getNumSubscribers() > 0) {
      keyframe_pub_.publish(
          ros_bridge::keyframe_positions_to_ros(mapping_.keyframes(), map_header));
    }
    if (path_pub_.getNumSubscribers() > 0) {
      path_pub_.publish(ros_bridge::path_to_ros(mapping_.trajectory(), stamps_, frames_.map));
    }
    if (surround_pub_.getNumSubscribers() > 0 && surround_throttle_.ready()) {
      surround_pub_.publish(ros_bridge::local_map_to_ros(mapping_.local_map(), map_header));
    }
  }

  MappingParams params_;
  LidarMapping mapping_;
  MappingOutput out_;
  bool uses_prior_;
  ros_bridge::FrameNames frames_;
  std::string sensor_frame_;
  std::vector<ros::Time> stamps_;  // of every mapped scan, for the path
  ros_bridge::ScanPairing pairing_;
  ros_bridge::Throttle surround_throttle_;  // the local map is large: at most once a period
  ros_bridge::ThrottledWarning warn_;
  ros_bridge::StageSummary summary_;
  std::vector<ros::Subscriber> subscriptions_;  // in Slot order
  ros::Publisher mapped_pub_, surround_pub_, keyframe_pub_, path_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
};

}  // namespace

int main(int argc, char** argv) {
  return ros_bridge::run_node<MapOptimization>(argc, argv, "map_optimization");
}
