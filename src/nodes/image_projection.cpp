// image_projection: the ambient-aware filter (LeGO-LOAM's imageProjection plus the skeleton,
// mu and the adaptive beta0) on every scan of velodyne_points.

#include <adaptive_lego_loam/DegenerationState.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/MarkerArray.h>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/degeneration_conversions.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_logging.h"
#include "adaptive_lego_loam/ros/segmented_cloud_conversions.h"

using namespace adaptive_lego_loam;

namespace {

class ImageProjection {
 public:
  ImageProjection(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config& config)
      : filter_(config),
        frames_(ros_bridge::load_frame_names(private_nh)),
        warn_("image_projection", private_nh.param("warning_period", 5.0)),
        summary_("image_projection", private_nh.param("summary_period", 10.0)) {
    const int queue = private_nh.param("queue_size", 5);
    segmented_pub_ = nh.advertise<sensor_msgs::PointCloud2>("segmented_cloud", queue);
    info_pub_ = nh.advertise<CloudInfoMsg>("segmented_cloud_info", queue);
    outlier_pub_ = nh.advertise<sensor_msgs::PointCloud2>("outlier_cloud", queue);
    degeneration_pub_ = nh.advertise<DegenerationState>("degeneration", queue);
    ground_pub_ = nh.advertise<sensor_msgs::PointCloud2>("ground_cloud", 1);
    projected_pub_ = nh.advertise<sensor_msgs::PointCloud2>("full_cloud_projected", 1);
    skeleton_pub_ = nh.advertise<sensor_msgs::PointCloud2>("skeleton_cloud", 1);
    marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("degeneration_markers", 1);
    scan_sub_ = nh.subscribe("velodyne_points", queue, &ImageProjection::on_scan, this);
    ROS_INFO("image_projection: %s (%d x %d, %s beta0) on %s", config.source.c_str(),
             config.sensor.rows, config.sensor.columns,
             config.ambient.mode == Beta0Mode::kAdaptive ? "adaptive" : "fixed",
             scan_sub_.getTopic().c_str());
  }

 private:
  void on_scan(const sensor_msgs::PointCloud2ConstPtr& msg) {
    try {
      if (!filter(*msg)) return;
    } catch (const std::exception& e) {
      drop(e.what());
      return;
    }
    std_msgs::Header header = msg->header;
    if (header.frame_id.empty()) header.frame_id = frames_.sensor;
    publish(header);
    const StageTimes& times = filtered_.times();
    ROS_DEBUG("image_projection: scan at %.3f: %s", header.stamp.toSec(),
              ros_bridge::format_stage_times(times).c_str());
    summary_.add(times);
    if (const auto line = summary_.report()) ROS_INFO("%s", line->c_str());
  }

  // Runs the filter; false when the scan is dropped (logged).
  bool filter(const sensor_msgs::PointCloud2& msg) {
    const std::string& topic = scan_sub_.getTopic();
    const Scan scan = ros_bridge::from_ros(msg, topic);
    try {
      filter_.process(scan, filtered_);
    } catch (const std::invalid_argument& e) {  // e.g. the config wants rings the cloud lacks
      drop(topic + ": " + e.what());
      return false;
    }
    const std::string problem = projection_problem(filtered_.segmentation.image.stats());
    if (!problem.empty()) {
      drop(topic + ": " + problem);
      return false;
    }
    return true;
  }

  void drop(const std::string& why) { warn_("scan dropped: " + why); }

  void publish(const std_msgs::Header& header) {
    const SegmentationResult& segmentation = filtered_.segmentation;
    const auto messages = ros_bridge::segmented_cloud_to_ros(segmentation.cloud, header);
    // The cloud info last: feature_association pairs all three by stamp, in any order.
    segmented_pub_.publish(messages.cloud);
    outlier_pub_.publish(messages.outliers);
    info_pub_.publish(messages.info);
    const DegenerationState degeneration = ros_bridge::degeneration_to_ros(filtered_, header);
    degeneration_pub_.publish(degeneration);
    if (marker_pub_.getNumSubscribers() > 0) {
      marker_pub_.publish(ros_bridge::degeneration_markers(degeneration));
    }
    if (ground_pub_.getNumSubscribers() > 0) {
      ground_pub_.publish(ros_bridge::to_ros(segmentation.cloud.ground, header));
    }
    if (projected_pub_.getNumSubscribers() > 0) {
      projected_pub_.publish(
          ros_bridge::to_ros(ros_bridge::projected_points(segmentation.image), header, true));
    }
    if (skeleton_pub_.getNumSubscribers() > 0) {
      skeleton_pub_.publish(ros_bridge::to_ros(filtered_.skeleton_cloud(), header));
    }
  }

  AmbientFilter filter_;
  AmbientFilterResult filtered_;
  ros_bridge::FrameNames frames_;
  ros_bridge::ThrottledWarning warn_;
  ros_bridge::StageSummary summary_;
  ros::Subscriber scan_sub_;
  ros::Publisher segmented_pub_, info_pub_, outlier_pub_, degeneration_pub_;
  ros::Publisher ground_pub_, projected_pub_, skeleton_pub_, marker_pub_;
};

}  // namespace

int main(int argc, char** argv) {
  return ros_bridge::run_node<ImageProjection>(argc, argv, "image_projection");
}
