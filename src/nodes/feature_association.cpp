#include "feature_association.h"
#include "node_entry_points.h"

#include "adaptive_lego_loam/ros/feature_conversions.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/shared_publish.h"

namespace adaptive_lego_loam::nodes {

using ros_bridge::publish_shared;

FeatureAssociationNode::FeatureAssociationNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh,
                                               const Config& config)
    : config_(config),
      odometry_(config.sensor, config.features, config.odometry),
      frames_(ros_bridge::load_frame_names(private_nh)),
      pairing_("feature_association", {"segmented_cloud", "segmented_cloud_info", "outlier_cloud"},
               private_nh.param("max_pending_scans", 10), private_nh.param("warning_period", 5.0)),
      warn_("feature_association", private_nh.param("warning_period", 5.0)),
      summary_("feature_association", private_nh.param("summary_period", 10.0)),
      diagnostics_(nh, private_nh, "feature_association", config.sensor.name,
                   config.sensor.scan_period,
                   [this](ros_bridge::HealthStatus& status) { add_diagnostics(status); }) {
  const int queue = private_nh.param("queue_size", 5);
  corner_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_corner_last", queue);
  surface_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_surf_last", queue);
  outlier_pub_ = nh.advertise<sensor_msgs::PointCloud2>("outlier_cloud_last", queue);
  odometry_pub_ = nh.advertise<nav_msgs::Odometry>("laser_odom_to_init", queue);
  sharp_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_sharp", 1);
  flat_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_flat", 1);
  cloud_sub_ = nh.subscribe("segmented_cloud", queue, &FeatureAssociationNode::on_cloud, this);
  info_sub_ = nh.subscribe("segmented_cloud_info", queue, &FeatureAssociationNode::on_info, this);
  outlier_sub_ = nh.subscribe("outlier_cloud", queue, &FeatureAssociationNode::on_outliers, this);
  if (uses_mapped_motion(config.odometry, config.mapping)) {
    mapped_sub_ =
        nh.subscribe("aft_mapped_to_init", queue, &FeatureAssociationNode::on_mapped, this);
  }
}

// As the offline pipeline: the last motion as mapping refined it (aft_mapped_to_init's twist)
// de-skews and predicts the next scan. It is exact when mapping keeps up (the graph test plays
// each scan after the last one was mapped); a scan that arrives first uses the odometry's own.
// The motion model is per scan: after a gap (scans mapping dropped) the velocity is taken over
// one sensor period, not over the gap.
void FeatureAssociationNode::on_mapped(const nav_msgs::OdometryConstPtr& msg) {
  const std::optional<ros::Time> previous = last_mapped_stamp_;
  last_mapped_stamp_ = msg->header.stamp;
  if (!previous || msg->header.stamp <= *previous) return;
  if (!ros_bridge::has_mapped_motion(*msg)) return;
  const double gap = (msg->header.stamp - *previous).toSec();
  const double period = config_.sensor.scan_period;
  try {
    odometry_.use_mapped_motion(ros_bridge::motion_from_twist(
        msg->twist.twist, gap <= 1.5 * period ? gap : period, mapped_sub_.getTopic()));
  } catch (const std::exception& e) {
    warn_(std::string("mapped motion ignored: ") + e.what());
  }
}

void FeatureAssociationNode::add(Slot slot, const std_msgs::Header& header,
                                 ros_bridge::StampMatcher::Message msg) {
  const auto group = pairing_.add(slot, header.stamp, std::move(msg));
  for (; pairing_dropped_ < pairing_.dropped(); ++pairing_dropped_)
    diagnostics_.dropped("incomplete group");
  if (group) process(*group);
}

void FeatureAssociationNode::reset() {
  odometry_ = LidarOdometry(config_.sensor, config_.features, config_.odometry);
  last_mapped_stamp_.reset();
}

void FeatureAssociationNode::process(const ros_bridge::StampMatcher::Group& group) {
  const StampStep step = diagnostics_.received(group.stamp);
  if (step == StampStep::kDuplicate) {
    drop("duplicate stamp", "a scan with the stamp of the last one");
    return;
  }
  if (step == StampStep::kBackward) {
    ROS_WARN(
        "feature_association: time went back to %.3f s (a bag played again?): odometry "
        "reset",
        group.stamp.toSec());
    reset();
  }
  const auto cloud = group.get<sensor_msgs::PointCloud2>(kCloud);
  try {
    ros_bridge::segmented_cloud_from_ros(*cloud, *group.get<CloudInfoMsg>(kInfo),
                                         *group.get<sensor_msgs::PointCloud2>(kOutliers), topics(),
                                         received_);
    odometry_.process(received_.cloud, received_.has_time, out_);
  } catch (const std::exception& e) {
    drop("bad cloud", e.what());
    return;
  }
  if (out_.odometry.rejected) {
    ++rejected_motions_;
    warn_(
        "implausible scan-to-scan motion (odometry.max_speed, max_turn_rate_deg): the "
        "predicted motion kept");
  }
  std_msgs::Header header = cloud->header;
  if (header.frame_id.empty()) header.frame_id = frames_.sensor;
  publish(header);
  ROS_DEBUG("feature_association: scan at %.3f: %s", header.stamp.toSec(),
            ros_bridge::format_stage_times(out_.times).c_str());
  diagnostics_.processed(out_.times);
  summary_.add(out_.times);
  if (const auto line = summary_.report()) ROS_INFO("%s", line->c_str());
}

void FeatureAssociationNode::add_diagnostics(ros_bridge::HealthStatus& status) {
  const long rejected = rejected_motions_;
  status.add("odometry motions rejected (total)", std::to_string(rejected));
  if (rejected > rejected_motions_reported_) {
    status.raise(ros_bridge::HealthLevel::kWarn, "implausible odometry motions rejected");
  }
  rejected_motions_reported_ = rejected;
}

void FeatureAssociationNode::drop(const std::string& reason, const std::string& detail) {
  diagnostics_.dropped(reason);
  warn_("scan dropped: " + detail);
}

ros_bridge::SegmentedCloudTopics FeatureAssociationNode::topics() const {
  return {cloud_sub_.getTopic(), info_sub_.getTopic(), outlier_sub_.getTopic()};
}

// Features in the sensor frame at the end of the sweep; the pose in the odometry frame.
void FeatureAssociationNode::publish(const std_msgs::Header& header) {
  const FeatureSet& features = out_.features;
  publish_shared(corner_pub_, ros_bridge::cloud_to_ros(*features.less_sharp, header));
  publish_shared(surface_pub_, ros_bridge::cloud_to_ros(*features.less_flat, header));
  publish_shared(outlier_pub_, ros_bridge::cloud_to_ros(*features.outliers, header));
  if (sharp_pub_.getNumSubscribers() > 0) {
    publish_shared(sharp_pub_, ros_bridge::cloud_to_ros(*features.sharp, header));
  }
  if (flat_pub_.getNumSubscribers() > 0) {
    publish_shared(flat_pub_, ros_bridge::cloud_to_ros(*features.flat, header));
  }
  std_msgs::Header odometry_header = header;
  odometry_header.frame_id = frames_.odom;
  publish_shared(odometry_pub_,
                 ros_bridge::odometry_to_ros(out_.pose, odometry_header, header.frame_id));
}

int run_feature_association(int argc, char** argv) {
  return ros_bridge::run_node<FeatureAssociationNode>(argc, argv, "feature_association");
}

}  // namespace adaptive_lego_loam::nodes
