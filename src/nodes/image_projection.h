#pragma once
// image_projection: the ambient-aware filter (LeGO-LOAM's imageProjection plus the skeleton,
// mu and the adaptive beta0) on every scan of velodyne_points.

#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/projection/config_fit.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_diagnostics.h"
#include "adaptive_lego_loam/ros/node_logging.h"

namespace adaptive_lego_loam::nodes {

class ImageProjectionNode {
 public:
  ImageProjectionNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config& config);

 private:
  void on_scan(const sensor_msgs::PointCloud2ConstPtr& msg);
  // Runs the filter; false when the scan is dropped (logged and counted).
  bool filter(const sensor_msgs::PointCloud2& msg);
  void drop(const std::string& reason, const std::string& detail);
  void publish(const std_msgs::Header& header);
  void add_diagnostics(ros_bridge::HealthStatus& status) const;

  Config config_;
  AmbientFilter filter_;
  Scan scan_;  // the latest message's points; its buffer is reused
  AmbientFilterResult filtered_;
  bool filtered_once_ = false;
  std::unique_ptr<ConfigFitWarning> fit_;  // made once the topic is known
  ros_bridge::FrameNames frames_;
  ros_bridge::ThrottledWarning warn_;
  ros_bridge::StageSummary summary_;
  ros::Subscriber scan_sub_;
  ros::Publisher segmented_pub_, info_pub_, outlier_pub_, degeneration_pub_;
  ros::Publisher ground_pub_, projected_pub_, skeleton_pub_, marker_pub_;
  ros_bridge::NodeDiagnostics diagnostics_;
};

}  // namespace adaptive_lego_loam::nodes
