// feature_association: de-skewing, feature extraction and scan-to-scan odometry (LeGO-LOAM's
// featureAssociation) on image_projection's segmented cloud, cloud info and outlier cloud.

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include <optional>

#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"
#include "adaptive_lego_loam/ros/feature_conversions.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_logging.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/segmented_cloud_conversions.h"
#include "adaptive_lego_loam/ros/stamp_matcher.h"

using namespace adaptive_lego_loam;

namespace {

enum Slot : std::size_t { kCloud, kInfo, kOutliers };

class FeatureAssociation {
 public:
  FeatureAssociation(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config& config)
      : odometry_(config.sensor, config.features, config.odometry),
        frames_(ros_bridge::load_frame_names(private_nh)),
        pairing_(
            "feature_association", {"segmented_cloud", "segmented_cloud_info", "outlier_cloud"},
            private_nh.param("max_pending_scans", 10), private_nh.param("warning_period", 5.0)),
        warn_("feature_association", private_nh.param("warning_period", 5.0)),
        summary_("feature_association", private_nh.param("summary_period", 10.0)) {
    const int queue = private_nh.param("queue_size", 5);
    corner_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_corner_last", queue);
    surface_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_surf_last", queue);
    outlier_pub_ = nh.advertise<sensor_msgs::PointCloud2>("outlier_cloud_last", queue);
    odometry_pub_ = nh.advertise<nav_msgs::Odometry>("laser_odom_to_init", queue);
    sharp_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_sharp", 1);
    flat_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_flat", 1);
    cloud_sub_ = nh.subscribe("segmented_cloud", queue, &FeatureAssociation::on_cloud, this);
    info_sub_ = nh.subscribe("segmented_cloud_info", queue, &FeatureAssociation::on_info, this);
    outlier_sub_ = nh.subscribe("outlier_cloud", queue, &FeatureAssociation::on_outliers, this);
    if (uses_mapped_motion(config.odometry, config.mapping)) {
      mapped_sub_ = nh.subscribe("aft_mapped_to_init", queue, &FeatureAssociation::on_mapped, this);
    }
  }

 private:
  void on_cloud(const sensor_msgs::PointCloud2ConstPtr& msg) { add(kCloud, msg->header, msg); }
  void on_info(const CloudInfoMsg::ConstPtr& msg) { add(kInfo, msg->header, msg); }
  void on_outliers(const sensor_msgs::PointCloud2ConstPtr& msg) {
    add(kOutliers, msg->header, msg);
  }

  // As the offline pipeline: the last motion as mapping refined it de-skews and predicts the next
  // scan. It is exact when mapping keeps up (the graph test plays each scan after the last one
  // was mapped); a scan that arrives first uses the odometry's own motion.
  void on_mapped(const nav_msgs::OdometryConstPtr& msg) {
    try {
      odometry_.use_mapped_pose(ros_bridge::pose_from_ros(msg->pose.pose, mapped_sub_.getTopic()));
    } catch (const std::exception& e) {
      warn_(std::string("mapped pose ignored: ") + e.what());
    }
  }

  void add(Slot slot, const std_msgs::Header& header, ros_bridge::StampMatcher::Message msg) {
    if (const auto group = pairing_.add(slot, header.stamp, std::move(msg))) process(*group);
  }

  void process(const ros_bridge::StampMatcher::Group& group) {
    const auto cloud = group.get<sensor_msgs::PointCloud2>(kCloud);
    ros_bridge::ReceivedSegmentedCloud received;
    try {
      received = ros_bridge::segmented_cloud_from_ros(
          *cloud, *group.get<CloudInfoMsg>(kInfo), *group.get<sensor_msgs::PointCloud2>(kOutliers),
          topics());
      odometry_.process(received.cloud, received.has_time, out_);
    } catch (const std::exception& e) {
      warn_(std::string("scan dropped: ") + e.what());
      return;
    }
    std_msgs::Header header = cloud->header;
    if (header.frame_id.empty()) header.frame_id = frames_.sensor;
    publish(header);
    ROS_DEBUG("feature_association: scan at %.3f: %s", header.stamp.toSec(),
              ros_bridge::format_stage_times(out_.times).c_str());
    summary_.add(out_.times);
    if (const auto line = summary_.report()) ROS_INFO("%s", line->c_str());
  }

  ros_bridge::SegmentedCloudTopics topics() const {
    return {cloud_sub_.getTopic(), info_sub_.getTopic(), outlier_sub_.getTopic()};
  }

  // Features in the sensor frame at the end of the sweep; the pose in the odometry frame.
  void publish(const std_msgs::Header& header) {
    const FeatureSet& features = out_.features;
    corner_pub_.publish(ros_bridge::cloud_to_ros(*features.less_sharp, header));
    surface_pub_.publish(ros_bridge::cloud_to_ros(*features.less_flat, header));
    outlier_pub_.publish(ros_bridge::cloud_to_ros(*features.outliers, header));
    if (sharp_pub_.getNumSubscribers() > 0) {
      sharp_pub_.publish(ros_bridge::cloud_to_ros(*features.sharp, header));
    }
    if (flat_pub_.getNumSubscribers() > 0) {
      flat_pub_.publish(ros_bridge::cloud_to_ros(*features.flat, header));
    }
    std_msgs::Header odometry_header = header;
    odometry_header.frame_id = frames_.odom;
    odometry_pub_.publish(ros_bridge::odometry_to_ros(out_.pose, odometry_header, header.frame_id));
  }

  LidarOdometry odometry_;
  OdometryOutput out_;
  ros_bridge::FrameNames frames_;
  ros_bridge::ScanPairing pairing_;
  ros_bridge::ThrottledWarning warn_;
  ros_bridge::StageSummary summary_;
  ros::Subscriber cloud_sub_, info_sub_, outlier_sub_, mapped_sub_;
  ros::Publisher corner_pub_, surface_pub_, outlier_pub_, odometry_pub_, sharp_pub_, flat_pub_;
};

}  // namespace

int main(int argc, char** argv) {
  return ros_bridge::run_node<FeatureAssociation>(argc, argv, "feature_association");
}
