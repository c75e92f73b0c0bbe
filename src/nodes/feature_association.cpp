#include "feature_association.h"
#include "node_entry_points.h"

#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/Marker.h>

#include <cstdio>

#include "adaptive_lego_loam/ros/feature_conversions.h"
#include "adaptive_lego_loam/ros/motion_prior_conversions.h"
#include "adaptive_lego_loam/ros/motion_sensor_conversions.h"
#include "adaptive_lego_loam/ros/odometry_hold_conversions.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/shared_publish.h"

namespace adaptive_lego_loam::nodes {
namespace {

// The pose of `child` in `parent` from TF (a static transform), waiting up to `wait_s` of wall
// time for it: ROS time may stand still under use_sim_time.
std::optional<Eigen::Isometry3d> lookup_pose(const tf2_ros::Buffer& buffer,
                                             const std::string& parent, const std::string& child,
                                             double wait_s) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(wait_s);
  std::string error;
  while (!buffer.canTransform(parent, child, ros::Time(0), &error)) {
    if (ros::WallTime::now() >= deadline || !ros::ok()) return std::nullopt;
    ros::WallDuration(0.01).sleep();
  }
  return tf2::transformToEigen(buffer.lookupTransform(parent, child, ros::Time(0)));
}

std::string describe_extrinsic(const std::vector<double>& rpy_deg, const std::vector<double>& xyz) {
  char text[160];
  std::snprintf(text, sizeof(text), "rpy %.4f %.4f %.4f deg, xyz %.4f %.4f %.4f m", rpy_deg[0],
                rpy_deg[1], rpy_deg[2], xyz[0], xyz[1], xyz[2]);
  return text;
}

// An input's extrinsic, `frame`'s pose in `sensor_frame`, from static TF; nothing when TF has
// none within `wait_s` (the config's `rpy_deg`, `xyz_m` hold). Logs which it is.
std::optional<Eigen::Isometry3d> extrinsic_from_tf(
    const tf2_ros::Buffer& buffer, const std::string& input, const std::string& sensor_frame,
    const std::string& frame, const std::vector<double>& rpy_deg, const std::vector<double>& xyz_m,
    double wait_s) {
  const std::optional<Eigen::Isometry3d> pose =
      frame.empty() ? std::nullopt : lookup_pose(buffer, sensor_frame, frame, wait_s);
  if (!pose) {
    char wait[32];
    std::snprintf(wait, sizeof(wait), "%.1f s", wait_s);
    const std::string why =
        frame.empty() ? "its messages name no frame"
                      : "no transform " + sensor_frame + " -> " + frame + " in TF within " + wait;
    ROS_INFO("feature_association: %s extrinsic from the config (%s): %s", input.c_str(),
             why.c_str(), describe_extrinsic(rpy_deg, xyz_m).c_str());
    return std::nullopt;
  }
  std::vector<double> rpy, xyz;
  ros_bridge::set_extrinsic(*pose, rpy, xyz);
  ROS_INFO("feature_association: %s extrinsic from TF %s -> %s: %s", input.c_str(),
           sensor_frame.c_str(), frame.c_str(), describe_extrinsic(rpy, xyz).c_str());
  return pose;
}

}  // namespace

using ros_bridge::publish_shared;
using ros_bridge::ScanRelease;

FeatureAssociationNode::FeatureAssociationNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh,
                                               const Config& config)
    : config_(config),
      odometry_(config.sensor, config.features, config.odometry),
      workers_(ros_bridge::load_workers(private_nh)),
      frames_(ros_bridge::load_frame_names(private_nh)),
      pairing_("feature_association", {"segmented_cloud", "segmented_cloud_info", "outlier_cloud"},
               private_nh.param("max_pending_scans", 10), private_nh.param("warning_period", 5.0)),
      warn_("feature_association", private_nh.param("warning_period", 5.0)),
      summary_("feature_association", private_nh.param("summary_period", 10.0)),
      takes_mapped_motion_(uses_mapped_motion(config.odometry, config.mapping)),
      max_pending_(private_nh.param("max_pending_scans", 10)),
      tf_wait_s_(private_nh.param("tf_wait", 1.0)),
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
  if (config.odometry.follow_test_shift > 0.0)
    hold_pub_ = nh.advertise<OdometryHold>("odometry_hold", queue);
  cloud_sub_ = nh.subscribe("segmented_cloud", queue, &FeatureAssociationNode::on_cloud, this);
  info_sub_ = nh.subscribe("segmented_cloud_info", queue, &FeatureAssociationNode::on_info, this);
  outlier_sub_ = nh.subscribe("outlier_cloud", queue, &FeatureAssociationNode::on_outliers, this);
  // The motion sensors: off (nothing of them subscribed or published) unless a topic is given.
  ros_bridge::MotionSensorInputs inputs;
  const std::string imu_topic = private_nh.param<std::string>("imu_topic", "");
  const std::string wheel_topic = private_nh.param<std::string>("wheel_odom_topic", "");
  inputs.imu = !imu_topic.empty();
  inputs.wheel = !wheel_topic.empty();
  if (!inputs.any()) {
    if (takes_mapped_motion_) {
      mapped_sub_ =
          nh.subscribe("aft_mapped_to_init", queue, &FeatureAssociationNode::on_mapped, this);
    }
    return;
  }
  const double timeout = private_nh.param("motion_sensor_timeout", 2.0 * config.sensor.scan_period);
  relay_.emplace(config, inputs, timeout);
  sensor_diagnostics_.emplace(inputs.imu ? nh.resolveName(imu_topic) : "",
                              inputs.wheel ? nh.resolveName(wheel_topic) : "");
  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_);
  // A large queue: samples come at up to 1 kHz and each one counts.
  if (inputs.imu) imu_sub_ = nh.subscribe(imu_topic, 2000, &FeatureAssociationNode::on_imu, this);
  if (inputs.wheel) {
    wheel_sub_ = nh.subscribe(wheel_topic, 500, &FeatureAssociationNode::on_wheel_odometry, this);
  }
  map_match_sub_ = nh.subscribe("map_match", queue, &FeatureAssociationNode::on_map_match, this);
  priors_pub_ = nh.advertise<MotionPriors>("motion_priors", queue);
  gravity_pub_ = nh.advertise<visualization_msgs::Marker>("gravity_marker", 1);
  release_timer_ =
      nh.createSteadyTimer(ros::WallDuration(timeout / 4.0),
                           [this](const ros::SteadyTimerEvent&) { release_pending(); });
  const std::string what = (inputs.imu ? " IMU on " + imu_topic : "") +
                           (inputs.wheel ? " wheel odometry on " + wheel_topic : "");
  ROS_INFO("feature_association: motion sensors:%s", what.c_str());
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

void FeatureAssociationNode::on_imu(const sensor_msgs::ImuConstPtr& msg) {
  if (!imu_frame_) imu_frame_ = msg->header.frame_id;
  relay_->add_imu(ros_bridge::imu_from_ros(*msg), ros_bridge::steady_seconds());
  release_pending();
}

void FeatureAssociationNode::on_wheel_odometry(const nav_msgs::OdometryConstPtr& msg) {
  // The twist is in the child frame; without one, in ~base_frame.
  if (!wheel_frame_)
    wheel_frame_ = msg->child_frame_id.empty() ? frames_.base : msg->child_frame_id;
  relay_->add_wheel(ros_bridge::wheel_odometry_from_ros(*msg), ros_bridge::steady_seconds());
  release_pending();
}

// What mapping saw of a scan teaches the motion sensors, before the next scan is predicted, and
// gives the odometry its motion model (as on_mapped without motion sensors, but from the same
// message: the next scan is released when it came).
void FeatureAssociationNode::on_map_match(const MapMatchConstPtr& msg) {
  const std::optional<ros::Time> previous = last_mapped_stamp_;
  last_mapped_stamp_ = msg->header.stamp;
  try {
    const ros_bridge::MappingFeedback feedback =
        ros_bridge::mapping_feedback_from_ros(*msg, map_match_sub_.getTopic());
    relay_->add_feedback(msg->header.stamp.toSec(), feedback.matched_motion(), feedback.information,
                         feedback.motion_prior);
    if (takes_mapped_motion_ && feedback.motion && previous && msg->header.stamp > *previous) {
      const double gap = (msg->header.stamp - *previous).toSec();
      const double period = config_.sensor.scan_period;
      odometry_.use_mapped_motion(
          gap <= 1.5 * period
              ? *feedback.motion
              : ros_bridge::motion_from_twist(ros_bridge::motion_to_twist(*feedback.motion, gap),
                                              period, map_match_sub_.getTopic()));
    }
  } catch (const std::exception& e) {
    warn_(std::string("map match ignored: ") + e.what());
  }
  release_pending();
}

void FeatureAssociationNode::add(Slot slot, const std_msgs::Header& header,
                                 ros_bridge::StampMatcher::Message msg) {
  auto group = pairing_.add(slot, header.stamp, std::move(msg));
  for (; pairing_dropped_ < pairing_.dropped(); ++pairing_dropped_)
    diagnostics_.dropped("incomplete group");
  if (!group) return;
  if (!relay_) {
    process(*group);
    return;
  }
  pending_.push_back({std::move(*group), ros_bridge::steady_seconds()});
  release_pending();
}

void FeatureAssociationNode::release_pending() {
  while (!pending_.empty()) {
    const PendingScan& scan = pending_.front();
    ScanRelease release =
        relay_->release(scan.group.stamp.toSec(), scan.since_s, ros_bridge::steady_seconds());
    if (release == ScanRelease::kWait) {
      if (pending_.size() <= max_pending_) return;
      release = ScanRelease::kTimeout;  // too many held: the oldest goes on
    }
    const ros_bridge::StampMatcher::Group group = std::move(pending_.front().group);
    pending_.pop_front();
    process(group, release);
  }
}

void FeatureAssociationNode::reset() {
  odometry_ = LidarOdometry(config_.sensor, config_.features, config_.odometry);
  last_mapped_stamp_.reset();
  if (relay_) relay_->reset();
}

void FeatureAssociationNode::resolve_extrinsics(const std::string& sensor_frame) {
  if (relay_->inputs().imu && imu_frame_ && !imu_extrinsic_resolved_) {
    imu_extrinsic_resolved_ = true;
    const ImuParams& config = config_.imu;
    if (const auto pose =
            extrinsic_from_tf(*tf_buffer_, "IMU", sensor_frame, *imu_frame_,
                              config.extrinsic_rpy_deg, config.extrinsic_xyz_m, tf_wait_s_)) {
      relay_->set_lidar_from_imu(*pose);
      sensor_diagnostics_->set_imu_extrinsic_source("TF " + sensor_frame + " -> " + *imu_frame_);
    }
  }
  if (relay_->inputs().wheel && wheel_frame_ && !wheel_extrinsic_resolved_) {
    wheel_extrinsic_resolved_ = true;
    const WheelOdometryParams& config = config_.wheel_odometry;
    if (const auto pose =
            extrinsic_from_tf(*tf_buffer_, "wheel odometry", sensor_frame, *wheel_frame_,
                              config.extrinsic_rpy_deg, config.extrinsic_xyz_m, tf_wait_s_)) {
      relay_->set_lidar_from_base(*pose);
      sensor_diagnostics_->set_wheel_extrinsic_source("TF " + sensor_frame + " -> " +
                                                      *wheel_frame_);
    }
  }
}

const MotionPrediction* FeatureAssociationNode::predict(const std_msgs::Header& header,
                                                        ScanRelease release, StageTimes& times) {
  resolve_extrinsics(header.frame_id);
  const std::string missing = relay_->missing(header.stamp.toSec());
  Stopwatch watch;
  const MotionPrediction* prediction = relay_->predict(
      header.stamp.toSec(), config_.sensor.scan_period, release, ros_bridge::steady_seconds());
  times.add("motion_sensors", watch.lap_ms());
  for (const ros_bridge::SampleFaultReport& fault : relay_->take_faults()) {
    if (fault.first) {
      ROS_WARN("feature_association: %s (further ones are counted on /diagnostics)",
               fault.describe().c_str());
    }
  }
  if (release == ScanRelease::kTimeout) {
    warn_("scan at " + std::to_string(header.stamp.toSec()) + " s processed without " +
          (missing.empty() ? "waiting: more scans held than ~max_pending_scans"
                           : missing + " (~motion_sensor_timeout)"));
  }
  return prediction;
}

void FeatureAssociationNode::process(const ros_bridge::StampMatcher::Group& group,
                                     ScanRelease release) {
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
  std_msgs::Header header = cloud->header;
  if (header.frame_id.empty()) header.frame_id = frames_.sensor;
  const MotionPrediction* prediction = nullptr;
  StageTimes times;
  try {
    ros_bridge::segmented_cloud_from_ros(*cloud, *group.get<CloudInfoMsg>(kInfo),
                                         *group.get<sensor_msgs::PointCloud2>(kOutliers), topics(),
                                         received_);
    if (relay_) prediction = predict(header, release, times);
    const UseWorkers use_workers(workers_.get());
    odometry_.process(received_.cloud, received_.has_time, out_, prediction);
  } catch (const std::exception& e) {
    drop("bad cloud", e.what());
    return;
  }
  times.append(out_.times);
  if (out_.odometry.registered) remember_weakest(observability(out_.odometry.information));
  held_scans_ += out_.odometry.held_direction.has_value();
  if (out_.odometry.rejected) {
    ++rejected_motions_;
    warn_(
        "implausible scan-to-scan motion (odometry.max_speed, max_turn_rate_deg): the "
        "predicted motion kept");
  }
  publish(header, prediction);
  ROS_DEBUG("feature_association: scan at %.3f: %s", header.stamp.toSec(),
            ros_bridge::format_stage_times(times).c_str());
  diagnostics_.processed(times);
  summary_.add(times);
  if (const auto line = summary_.report()) ROS_INFO("%s", line->c_str());
}

void FeatureAssociationNode::add_diagnostics(ros_bridge::HealthStatus& status) {
  const long rejected = rejected_motions_;
  status.add("odometry motions rejected (total)", std::to_string(rejected));
  if (rejected > rejected_motions_reported_) {
    status.raise(ros_bridge::HealthLevel::kWarn, "implausible odometry motions rejected");
  }
  rejected_motions_reported_ = rejected;
  if (hold_pub_) {
    status.add("scans held along their travel (follow test, total)", std::to_string(held_scans_));
  }
  {
    std::lock_guard<std::mutex> lock(weakest_mutex_);
    if (!weakest_text_.empty())
      status.add("weakest direction (sensor frame, scan-to-scan)", weakest_text_);
  }
  if (relay_) sensor_diagnostics_->add_to(*relay_, status);
}

void FeatureAssociationNode::remember_weakest(const Observability& seen) {
  const std::string text =
      ros_bridge::direction_text(seen.weakest_direction(), seen.weakest_sigma());
  std::lock_guard<std::mutex> lock(weakest_mutex_);
  weakest_text_ = text;
}

void FeatureAssociationNode::drop(const std::string& reason, const std::string& detail) {
  diagnostics_.dropped(reason);
  warn_("scan dropped: " + detail);
}

ros_bridge::SegmentedCloudTopics FeatureAssociationNode::topics() const {
  return {cloud_sub_.getTopic(), info_sub_.getTopic(), outlier_sub_.getTopic()};
}

// Features in the sensor frame at the end of the sweep; the pose in the odometry frame.
void FeatureAssociationNode::publish(const std_msgs::Header& header,
                                     const MotionPrediction* prediction) {
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
  nav_msgs::Odometry odometry =
      ros_bridge::odometry_to_ros(out_.pose, odometry_header, header.frame_id);
  ros_bridge::set_pose_covariance(out_.pose_covariance, odometry.pose);
  publish_shared(odometry_pub_, std::move(odometry));
  // Every scan's, so that map_optimization pairs it.
  if (hold_pub_) publish_shared(hold_pub_, ros_bridge::odometry_hold_to_ros(out_.odometry, header));
  if (!relay_) return;
  // Every scan's, so that map_optimization pairs it; both flags false when LiDAR-only.
  MotionPriors priors = ros_bridge::motion_priors_to_ros(prediction, header);
  if (gravity_pub_.getNumSubscribers() > 0) {
    publish_shared(gravity_pub_, ros_bridge::gravity_marker(priors));
  }
  publish_shared(priors_pub_, std::move(priors));
}

int run_feature_association(int argc, char** argv) {
  return ros_bridge::run_node<FeatureAssociationNode>(argc, argv, "feature_association");
}

}  // namespace adaptive_lego_loam::nodes
