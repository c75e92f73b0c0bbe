#pragma once
// feature_association: de-skewing, feature extraction and scan-to-scan odometry (LeGO-LOAM's
// featureAssociation) on image_projection's segmented cloud, cloud info and outlier cloud.

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include <atomic>
#include <optional>

#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"
#include "adaptive_lego_loam/ros/cloud_info_msg.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_diagnostics.h"
#include "adaptive_lego_loam/ros/node_logging.h"
#include "adaptive_lego_loam/ros/segmented_cloud_conversions.h"
#include "adaptive_lego_loam/ros/stamp_matcher.h"

namespace adaptive_lego_loam::nodes {

class FeatureAssociationNode {
 public:
  FeatureAssociationNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config& config);

 private:
  enum Slot : std::size_t { kCloud, kInfo, kOutliers };

  void on_cloud(const sensor_msgs::PointCloud2ConstPtr& msg) { add(kCloud, msg->header, msg); }
  void on_info(const CloudInfoMsg::ConstPtr& msg) { add(kInfo, msg->header, msg); }
  void on_outliers(const sensor_msgs::PointCloud2ConstPtr& msg) {
    add(kOutliers, msg->header, msg);
  }
  void on_mapped(const nav_msgs::OdometryConstPtr& msg);
  void add(Slot slot, const std_msgs::Header& header, ros_bridge::StampMatcher::Message msg);
  void process(const ros_bridge::StampMatcher::Group& group);
  void drop(const std::string& reason, const std::string& detail);
  void reset();
  ros_bridge::SegmentedCloudTopics topics() const;
  void publish(const std_msgs::Header& header);
  void add_diagnostics(ros_bridge::HealthStatus& status);

  Config config_;
  LidarOdometry odometry_;
  ros_bridge::ReceivedSegmentedCloud received_;  // the latest scan; its buffers are reused
  OdometryOutput out_;
  ros_bridge::FrameNames frames_;
  ros_bridge::ScanPairing pairing_;
  long pairing_dropped_ = 0;  // of pairing_.dropped() already counted
  // Implausible registrations whose prediction was kept (OdometryResult::rejected); the
  // diagnostics timer reads it.
  std::atomic<long> rejected_motions_{0};
  long rejected_motions_reported_ = 0;
  std::optional<ros::Time> last_mapped_stamp_;
  ros_bridge::ThrottledWarning warn_;
  ros_bridge::StageSummary summary_;
  ros::Subscriber cloud_sub_, info_sub_, outlier_sub_, mapped_sub_;
  ros::Publisher corner_pub_, surface_pub_, outlier_pub_, odometry_pub_, sharp_pub_, flat_pub_;
  ros_bridge::NodeDiagnostics diagnostics_;
};

}  // namespace adaptive_lego_loam::nodes
