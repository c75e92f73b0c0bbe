#include "image_projection.h"
#include "node_entry_points.h"

#include <adaptive_lego_loam/DegenerationState.h>
#include <visualization_msgs/MarkerArray.h>

#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/degeneration_conversions.h"
#include "adaptive_lego_loam/ros/segmented_cloud_conversions.h"
#include "adaptive_lego_loam/ros/shared_publish.h"

namespace adaptive_lego_loam::nodes {

using ros_bridge::publish_shared;

ImageProjectionNode::ImageProjectionNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh,
                                         const Config& config)
    : config_(config),
      filter_(config),
      frames_(ros_bridge::load_frame_names(private_nh)),
      warn_("image_projection", private_nh.param("warning_period", 5.0)),
      summary_("image_projection", private_nh.param("summary_period", 10.0)),
      diagnostics_(nh, private_nh, "image_projection", config.sensor.name,
                   config.sensor.scan_period,
                   [this](ros_bridge::HealthStatus& status) { add_diagnostics(status); }) {
  const int queue = private_nh.param("queue_size", 5);
  segmented_pub_ = nh.advertise<sensor_msgs::PointCloud2>("segmented_cloud", queue);
  info_pub_ = nh.advertise<CloudInfoMsg>("segmented_cloud_info", queue);
  outlier_pub_ = nh.advertise<sensor_msgs::PointCloud2>("outlier_cloud", queue);
  degeneration_pub_ = nh.advertise<DegenerationState>("degeneration", queue);
  ground_pub_ = nh.advertise<sensor_msgs::PointCloud2>("ground_cloud", 1);
  projected_pub_ = nh.advertise<sensor_msgs::PointCloud2>("full_cloud_projected", 1);
  skeleton_pub_ = nh.advertise<sensor_msgs::PointCloud2>("skeleton_cloud", 1);
  marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("degeneration_markers", 1);
  scan_sub_ = nh.subscribe("velodyne_points", queue, &ImageProjectionNode::on_scan, this);
  diagnostics_.watch_input(scan_sub_.getTopic());
  fit_ = std::make_unique<ConfigFitWarning>(config.source, scan_sub_.getTopic());
  ROS_INFO("image_projection: %s (%d x %d, %s beta0) on %s", config.source.c_str(),
           config.sensor.rows, config.sensor.columns, to_string(config.ambient.mode),
           scan_sub_.getTopic().c_str());
}

void ImageProjectionNode::on_scan(const sensor_msgs::PointCloud2ConstPtr& msg) {
  const StampStep step = diagnostics_.received(msg->header.stamp);
  if (step == StampStep::kDuplicate) {
    drop("duplicate stamp", "a scan with the stamp of the last one");
    return;
  }
  if (step == StampStep::kBackward) {
    ROS_WARN("image_projection: time went back to %.3f s (a bag played again?): filter reset",
             msg->header.stamp.toSec());
    filter_.reset();
  }
  try {
    if (!filter(*msg)) return;
  } catch (const std::exception& e) {
    drop("bad cloud", e.what());
    return;
  }
  std_msgs::Header header = msg->header;
  if (header.frame_id.empty()) header.frame_id = frames_.sensor;
  publish(header);
  filtered_once_ = true;
  const StageTimes& times = filtered_.times();
  ROS_DEBUG("image_projection: scan at %.3f: %s", header.stamp.toSec(),
            ros_bridge::format_stage_times(times).c_str());
  diagnostics_.processed(times);
  summary_.add(times);
  if (const auto line = summary_.report()) ROS_INFO("%s", line->c_str());
}

bool ImageProjectionNode::filter(const sensor_msgs::PointCloud2& msg) {
  const std::string& topic = scan_sub_.getTopic();
  ros_bridge::from_ros(msg, topic, scan_, {config_.sensor.scan_period});
  try {
    filter_.process(scan_, filtered_);
  } catch (const std::invalid_argument& e) {  // e.g. the config wants rings the cloud lacks
    drop("bad cloud", topic + ": " + e.what());
    return false;
  }
  const std::string problem = projection_problem(filtered_.segmentation.image.stats());
  if (!problem.empty()) {
    drop("bad cloud", topic + ": " + problem);
    return false;
  }
  if (const auto warning = fit_->check(config_.sensor, filtered_.segmentation.image,
                                       rows_from_ring(config_.sensor, scan_.has_ring))) {
    ROS_WARN("image_projection: %s", warning->c_str());
  }
  return true;
}

void ImageProjectionNode::drop(const std::string& reason, const std::string& detail) {
  diagnostics_.dropped(reason, detail);
  warn_("scan dropped: " + detail);
}

void ImageProjectionNode::publish(const std_msgs::Header& header) {
  const SegmentationResult& segmentation = filtered_.segmentation;
  auto messages = ros_bridge::segmented_cloud_to_ros(segmentation.cloud, header);
  // The cloud info last: feature_association pairs all three by stamp, in any order.
  publish_shared(segmented_pub_, std::move(messages.cloud));
  publish_shared(outlier_pub_, std::move(messages.outliers));
  publish_shared(info_pub_, std::move(messages.info));
  DegenerationState degeneration = ros_bridge::degeneration_to_ros(filtered_, header);
  if (marker_pub_.getNumSubscribers() > 0) {
    publish_shared(marker_pub_, ros_bridge::degeneration_markers(degeneration));
  }
  publish_shared(degeneration_pub_, std::move(degeneration));
  if (ground_pub_.getNumSubscribers() > 0) {
    publish_shared(ground_pub_, ros_bridge::to_ros(segmentation.cloud.ground, header));
  }
  if (projected_pub_.getNumSubscribers() > 0) {
    publish_shared(
        projected_pub_,
        ros_bridge::to_ros(ros_bridge::projected_points(segmentation.image), header, true));
  }
  if (skeleton_pub_.getNumSubscribers() > 0) {
    publish_shared(skeleton_pub_, ros_bridge::to_ros(filtered_.skeleton_cloud(), header));
  }
}

void ImageProjectionNode::add_diagnostics(ros_bridge::HealthStatus& status) const {
  if (!filtered_once_) return;
  status.add("mu", filtered_.mu);
  status.add("beta0 (deg)", filtered_.beta0_deg);
  status.add("every cluster kept", filtered_.every_cluster_kept ? "yes" : "no");
  status.add("skeleton points", std::to_string(filtered_.skeleton_points));
  status.add("skeleton share", filtered_.skeleton_share());
  status.add("fragment smoothness", filtered_.fragment_smoothness);
  status.add("structure share", filtered_.structure_share);
  status.add("beta0 mode", to_string(config_.ambient.mode));
  for (const std::string& problem : fit_->seen())
    status.raise(ros_bridge::HealthLevel::kWarn, "the config does not fit: " + problem);
}

int run_image_projection(int argc, char** argv) {
  return ros_bridge::run_node<ImageProjectionNode>(argc, argv, "image_projection");
}

}  // namespace adaptive_lego_loam::nodes
