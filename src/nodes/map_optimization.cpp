#include "map_optimization.h"
#include "node_entry_points.h"

#include <nav_msgs/Path.h>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/map_files.h"
#include "adaptive_lego_loam/io/process_memory.h"
#include "adaptive_lego_loam/ros/degeneration_conversions.h"
#include "adaptive_lego_loam/ros/feature_conversions.h"
#include "adaptive_lego_loam/ros/motion_prior_conversions.h"
#include "adaptive_lego_loam/ros/odometry_hold_conversions.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/shared_publish.h"
#include "adaptive_lego_loam/ros/uncertainty_markers.h"

namespace adaptive_lego_loam::nodes {
namespace {

// The optional slots after the fixed ones, in this order (MapOptimizationNode::priors_slot,
// hold_slot).
std::vector<std::string> slot_names(bool with_motion_priors, bool with_hold) {
  std::vector<std::string> names = {"laser_cloud_corner_last", "laser_cloud_surf_last",
                                    "outlier_cloud_last", "laser_odom_to_init", "degeneration"};
  if (with_motion_priors) names.push_back("motion_priors");
  if (with_hold) names.push_back("odometry_hold");
  return names;
}

// ~initial_pose "x y z yaw_deg" (empty: the map's origin).
Eigen::Isometry3d initial_pose_param(const ros::NodeHandle& private_nh) {
  const std::string text = private_nh.param<std::string>("initial_pose", "");
  if (text.empty()) return Eigen::Isometry3d::Identity();
  std::istringstream fields(text);
  double x = 0, y = 0, z = 0, yaw_deg = 0;
  fields >> x >> y >> z >> yaw_deg;
  if (!fields || !(fields >> std::ws).eof()) {
    throw ConfigError(private_nh.resolveName("initial_pose") + ": \"" + text +
                      "\": expected \"x y z yaw_deg\"");
  }
  return initial_pose(x, y, z, yaw_deg);
}

}  // namespace

using ros_bridge::publish_shared;

MapOptimizationNode::MapOptimizationNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh,
                                         const Config& config)
    : config_(config),
      map_folder_(private_nh.param<std::string>("map", "")),
      initial_pose_(initial_pose_param(private_nh)),
      save_on_exit_(private_nh.param<std::string>("save_map_on_exit", "")),
      workers_(ros_bridge::load_workers(private_nh)),
      uses_motion_sensors_(private_nh.param("motion_sensors", false)),
      uses_odometry_hold_(config.odometry.follow_test_shift > 0.0),
      degenerate_state_(config.mapping.degenerate_translation_sigma),
      frames_(ros_bridge::load_frame_names(private_nh)),
      pairing_("map_optimization", slot_names(uses_motion_sensors_, uses_odometry_hold_),
               private_nh.param("max_pending_scans", 10), private_nh.param("warning_period", 5.0)),
      surround_throttle_(private_nh.param("surround_period", 1.0)),
      path_throttle_(private_nh.param("path_period", 1.0)),
      warn_("map_optimization", private_nh.param("warning_period", 5.0)),
      summary_("map_optimization", private_nh.param("summary_period", 10.0)),
      diagnostics_(nh, private_nh, "map_optimization", config.sensor.name,
                   config.sensor.scan_period,
                   [this](ros_bridge::HealthStatus& status) { add_diagnostics(status); }) {
  if (!map_folder_.empty()) {
    SavedMap map = load_map(map_folder_);
    if (!map.description.sensor.empty() && map.description.sensor != config.sensor.name) {
      ROS_WARN("map_optimization: the map %s was made with sensor %s, this config is for %s",
               map_folder_.c_str(), map.description.sensor.c_str(), config.sensor.name.c_str());
    }
    map_keyframes_ = std::move(map.keyframes);
    ROS_INFO("map_optimization: localizing on %s (%zu keyframes); waiting for the first scan",
             map_folder_.c_str(), map_keyframes_.size());
  }
  mapping_ = make_mapping();
  const int queue = private_nh.param("queue_size", 5);
  mapped_pub_ = nh.advertise<nav_msgs::Odometry>("aft_mapped_to_init", queue);
  surround_pub_ = nh.advertise<sensor_msgs::PointCloud2>("laser_cloud_surround", 1);
  keyframe_pub_ = nh.advertise<sensor_msgs::PointCloud2>("key_pose_origin", 1);
  path_pub_ = nh.advertise<nav_msgs::Path>("path", 1);
  map_match_pub_ = nh.advertise<MapMatch>("map_match", queue);
  uncertainty_pub_ = nh.advertise<visualization_msgs::MarkerArray>("pose_uncertainty_markers", 1);
  subscriptions_.push_back(
      nh.subscribe("laser_cloud_corner_last", queue, &MapOptimizationNode::on_corners, this));
  subscriptions_.push_back(
      nh.subscribe("laser_cloud_surf_last", queue, &MapOptimizationNode::on_surfaces, this));
  subscriptions_.push_back(
      nh.subscribe("outlier_cloud_last", queue, &MapOptimizationNode::on_outliers, this));
  subscriptions_.push_back(
      nh.subscribe("laser_odom_to_init", queue, &MapOptimizationNode::on_odometry, this));
  // image_projection is a whole stage ahead: a larger queue keeps its messages until the
  // features of the same scan arrive.
  subscriptions_.push_back(
      nh.subscribe("degeneration", 4 * queue, &MapOptimizationNode::on_degeneration, this));
  if (uses_motion_sensors_) {
    subscriptions_.push_back(
        nh.subscribe("motion_priors", queue, &MapOptimizationNode::on_motion_priors, this));
  }
  if (uses_odometry_hold_) {
    subscriptions_.push_back(
        nh.subscribe("odometry_hold", queue, &MapOptimizationNode::on_odometry_hold, this));
  }
  if (mapping_->localizing()) {
    initial_pose_sub_ = nh.subscribe("initialpose", 1, &MapOptimizationNode::on_initial_pose, this);
  }
  ros::AdvertiseServiceOptions service = ros::AdvertiseServiceOptions::create<SaveMap>(
      "save_map",
      [this](SaveMap::Request& request, SaveMap::Response& response) {
        return on_save_map(request, response);
      },
      ros::VoidPtr(), &service_queue_);
  save_service_ = private_nh.advertiseService(service);
  service_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &service_queue_);
  service_spinner_->start();
}

MapOptimizationNode::~MapOptimizationNode() {
  service_spinner_->stop();
  if (save_on_exit_.empty()) return;
  try {
    ROS_INFO("map_optimization: %s", save(save_on_exit_, 0.0).message.c_str());
  } catch (const std::exception& e) {
    ROS_ERROR("map_optimization: the map was not saved on exit: %s", e.what());
  }
}

std::unique_ptr<LidarMapping> MapOptimizationNode::make_mapping() const {
  auto mapping = map_folder_.empty()
                     ? std::make_unique<LidarMapping>(config_)
                     : std::make_unique<LidarMapping>(config_, map_keyframes_, initial_pose_);
  mapping->keep_trajectory(false);  // the path is the keyframes'
  return mapping;
}

void MapOptimizationNode::on_initial_pose(
    const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg) {
  // rviz sends the pose in its fixed frame: only the map frame is the saved map's.
  if (!msg->header.frame_id.empty() && msg->header.frame_id != frames_.map) {
    warn_("initial pose ignored: it is in frame " + msg->header.frame_id + ", expected " +
          frames_.map + " (set rviz's fixed frame to " + frames_.map + ")");
    return;
  }
  try {
    const Eigen::Isometry3d pose = ros_bridge::pose_from_ros(msg->pose.pose, "initialpose");
    std::lock_guard<std::mutex> lock(mapping_mutex_);
    initial_pose_ = pose;  // also where a restart (time going back) starts from
    mapping_->relocalize(pose);
    drive_poses_.clear();  // the path starts again where the new pose puts the sensor
    drive_stamps_.clear();
    ROS_INFO("map_optimization: new initial pose (%.2f, %.2f, %.2f): aligning to the map",
             pose.translation().x(), pose.translation().y(), pose.translation().z());
  } catch (const std::exception& e) {
    warn_(std::string("initial pose ignored: ") + e.what());
  }
}

MapOptimizationNode::Saved MapOptimizationNode::save(const std::string& folder, double voxel_size) {
  std::vector<Keyframe> keyframes;
  MapDescription description{config_.source, config_.sensor.name, "map_optimization", 0};
  {
    std::lock_guard<std::mutex> lock(mapping_mutex_);
    if (mapping_->localizing()) {
      throw IoError("localizing on " + map_folder_ + ": the map is the loaded one, not saved");
    }
    keyframes = mapping_->keyframes();  // clouds shared, not copied
    description.frames = static_cast<int>(mapped_scans_);
  }
  const std::string absolute = std::filesystem::absolute(folder).string();
  save_map(absolute, keyframes, description, config_, voxel_size);
  return {"map of " + std::to_string(keyframes.size()) + " keyframes saved in " + absolute,
          static_cast<int>(keyframes.size())};
}

bool MapOptimizationNode::on_save_map(SaveMap::Request& request, SaveMap::Response& response) {
  try {
    if (request.folder.empty()) throw IoError("save_map: no folder given");
    const Saved saved = save(request.folder, request.voxel_size);
    response.message = saved.message;
    response.keyframes = saved.keyframes;
    response.success = true;
    ROS_INFO("map_optimization: %s", response.message.c_str());
  } catch (const std::exception& e) {
    response.success = false;
    response.message = e.what();
    ROS_ERROR("map_optimization: save_map failed: %s", e.what());
  }
  return true;  // the outcome is in the response
}

void MapOptimizationNode::add(std::size_t slot, const std_msgs::Header& header,
                              ros_bridge::StampMatcher::Message msg) {
  const auto group = pairing_.add(slot, header.stamp, std::move(msg));
  for (; pairing_dropped_ < pairing_.dropped(); ++pairing_dropped_)
    diagnostics_.dropped("incomplete group");
  if (group) process(*group);
}

void MapOptimizationNode::process(const ros_bridge::StampMatcher::Group& group) {
  const StampStep step = diagnostics_.received(group.stamp);
  if (step == StampStep::kDuplicate) {
    diagnostics_.dropped("duplicate stamp");
    warn_("scan dropped: a scan with the stamp of the last one");
    return;
  }
  if (step == StampStep::kBackward) {
    ROS_WARN("map_optimization: time went back to %.3f s (a bag played again?): %s",
             group.stamp.toSec(),
             map_folder_.empty() ? "the map starts over" : "localization starts over");
    std::lock_guard<std::mutex> lock(mapping_mutex_);
    mapping_ = make_mapping();
    degenerate_state_.reset();
    mapped_scans_ = 0;
    drive_poses_.clear();
    drive_stamps_.clear();
    last_stamp_.reset();
  }
  try {
    map_scan(group);
  } catch (const std::exception& e) {
    diagnostics_.dropped("bad cloud");
    warn_(std::string("scan dropped: ") + e.what());
    return;
  }
  ROS_DEBUG("map_optimization: scan at %.3f: %s%s", group.stamp.toSec(),
            ros_bridge::format_stage_times(out_.times).c_str(), out_.keyframe ? " (keyframe)" : "");
  if (out_.loop) log_loop(*out_.loop);
  if (out_.localization) log_localization(*out_.localization);
  diagnostics_.processed(out_.times);
  summary_.add(out_.times);
  if (const auto line = summary_.report()) ROS_INFO("%s", line->c_str());
}

void MapOptimizationNode::map_scan(const ros_bridge::StampMatcher::Group& group) {
  const auto odometry = group.get<nav_msgs::Odometry>(kOdometry);
  const FeatureSet features =
      ros_bridge::mapping_features_from_ros(*group.get<sensor_msgs::PointCloud2>(kCorners),
                                            *group.get<sensor_msgs::PointCloud2>(kSurfaces),
                                            *group.get<sensor_msgs::PointCloud2>(kOutliers),
                                            {topic(kCorners), topic(kSurfaces), topic(kOutliers)});
  const Eigen::Isometry3d odometry_pose =
      ros_bridge::pose_from_ros(odometry->pose.pose, topic(kOdometry));
  const DegenerationState& degeneration = *group.get<DegenerationState>(kDegeneration);
  const std::optional<WeakDirectionPrior> prior =
      ros_bridge::weak_direction_prior_from_ros(config_.mapping, degeneration);
  scene_ = ros_bridge::scene_degeneration_from_ros(degeneration);
  // The motion sensors' priors of the scan, as the offline pipeline passes them (none: nullptr).
  std::optional<MotionPrediction> sensors;
  if (uses_motion_sensors_) {
    sensors = ros_bridge::motion_priors_from_ros(*group.get<MotionPriors>(priors_slot()),
                                                 topic(priors_slot()));
    if (sensors->empty()) sensors.reset();
  }
  // The direction the odometry held at its guess (the follow test), as the offline pipeline
  // passes it.
  std::optional<Eigen::Vector3d> held;
  if (uses_odometry_hold_) {
    held = ros_bridge::odometry_held_from_ros(*group.get<OdometryHold>(hold_slot()),
                                              topic(hold_slot()));
  }
  {
    std::lock_guard<std::mutex> lock(mapping_mutex_);
    const UseWorkers use_workers(workers_.get());
    mapping_->process(features, odometry_pose, group.stamp.toSec(), prior, out_,
                      sensors ? &*sensors : nullptr, scene_, held);
    sensor_frame_ = odometry->child_frame_id.empty() ? frames_.sensor : odometry->child_frame_id;
    if (out_.match.matched)
      degenerate_state_.update(weakest_direction(out_.match, scene_, config_.mapping).sigma);
    ++mapped_scans_;
    if (mapping_->localizing() &&
        (drive_poses_.empty() ||
         (drive_poses_.back().translation() - out_.pose.translation()).norm() >= 1.0)) {
      drive_poses_.push_back(out_.pose);
      drive_stamps_.push_back(group.stamp);
      // The newest stretch only: hours of driving would otherwise grow it, and each /path with it.
      if (drive_poses_.size() >= 2 * kPathPoses) {
        drive_poses_.erase(drive_poses_.begin(), drive_poses_.end() - kPathPoses);
        drive_stamps_.erase(drive_stamps_.begin(), drive_stamps_.end() - kPathPoses);
      }
    }
    publish(group.stamp);
  }
  last_stamp_ = group.stamp;
  heap_trimmer_.after_scan();
}

nav_msgs::Path MapOptimizationNode::path(const ros::Time& stamp) const {
  std::vector<Eigen::Isometry3d> poses = drive_poses_;
  std::vector<ros::Time> stamps = drive_stamps_;
  if (!mapping_->localizing()) {
    for (const Keyframe& keyframe : mapping_->keyframes()) {
      poses.push_back(keyframe.pose);
      stamps.emplace_back(keyframe.stamp);
    }
  }
  poses.push_back(out_.pose);
  stamps.push_back(stamp);
  return ros_bridge::path_to_ros(poses, stamps, frames_.map);
}

// An attempt is reported on the scan it finished, some scans after its keyframe.
void MapOptimizationNode::log_loop(const LoopDetection& loop) const {
  if (loop.accepted()) {
    ROS_INFO("map_optimization: loop verified: keyframe %d to %d (%s, %.1f %% inliers)",
             loop.current_index, loop.matched_index, to_string(loop.source),
             100.0 * loop.inlier_ratio);
  } else {
    ROS_DEBUG("map_optimization: no loop at keyframe %d: %s (%.1f %% inliers)", loop.current_index,
              to_string(loop.status), 100.0 * loop.inlier_ratio);
  }
}

void MapOptimizationNode::log_localization(const LocalizationStatus& status) {
  lost_scans_ += status.state == LocalizationState::kLost;
  if (last_state_ && *last_state_ == status.state) return;
  last_state_ = status.state;
  if (status.state == LocalizationState::kTracking) {
    ROS_INFO("map_optimization: localized on the map (%.1f %% inliers)",
             status.alignment ? 100.0 * status.alignment->inlier_ratio : 0.0);
  } else if (status.state == LocalizationState::kLost) {
    const std::string alignment =
        status.alignment ? std::string(", alignment: ") + to_string(status.alignment->status) : "";
    ROS_WARN(
        "map_optimization: localization lost (%.0f %% of the features match the map%s); "
        "following the odometry and trying again from there",
        100.0 * status.match_ratio, alignment.c_str());
  }
}

void MapOptimizationNode::publish(const ros::Time& stamp) {
  std_msgs::Header map_header;
  map_header.stamp = stamp;
  map_header.frame_id = frames_.map;
  nav_msgs::Odometry mapped = ros_bridge::odometry_to_ros(out_.pose, map_header, sensor_frame_);
  const Matrix6d covariance = mapped_pose_covariance(out_.match, starts_map(out_), scene_);
  ros_bridge::set_pose_covariance(covariance, mapped.pose);
  // The mapped motion, without the map frame's jumps: feature_association's motion model.
  if (out_.motion && last_stamp_ && stamp > *last_stamp_) {
    mapped.twist.twist = ros_bridge::motion_to_twist(*out_.motion, (stamp - *last_stamp_).toSec());
  } else {
    ros_bridge::mark_no_mapped_motion(mapped);
  }
  // What the motion sensors learn from (before the pose: whoever waits for the pose has it).
  std_msgs::Header sensor_header = map_header;
  sensor_header.frame_id = sensor_frame_;
  MapMatchResult match = out_.match;
  match.information = sensor_feedback_information(out_.match, scene_);
  publish_shared(map_match_pub_, ros_bridge::map_match_to_ros(match, out_.motion, sensor_header));
  publish_shared(mapped_pub_, std::move(mapped));
  if (uncertainty_pub_.getNumSubscribers() > 0) {
    WeakestDirection lidar;  // unmatched: nothing fixes the pose
    lidar.degenerate = true;
    if (out_.match.matched) lidar = weakest_direction(out_.match, scene_, config_.mapping);
    publish_shared(uncertainty_pub_,
                   ros_bridge::uncertainty_markers(sensor_header, covariance, lidar));
  }
  tf_broadcaster_.sendTransform(
      ros_bridge::transform_to_ros(mapping_->fusion().correction(), map_header, frames_.odom));
  if (out_.keyframe && keyframe_pub_.getNumSubscribers() > 0) {
    publish_shared(keyframe_pub_,
                   ros_bridge::keyframe_positions_to_ros(mapping_->keyframes(), map_header));
  }
  if (path_pub_.getNumSubscribers() > 0 && (out_.loop_closed || path_throttle_.ready())) {
    publish_shared(path_pub_, path(stamp));
  }
  if (surround_pub_.getNumSubscribers() > 0 && surround_throttle_.ready()) {
    publish_shared(surround_pub_, ros_bridge::local_map_to_ros(mapping_->local_map(), map_header));
  }
}

void MapOptimizationNode::add_diagnostics(ros_bridge::HealthStatus& status) const {
  std::lock_guard<std::mutex> lock(mapping_mutex_);
  if (out_.match.matched) {
    const WeakestDirection weakest = weakest_direction(out_.match, scene_, config_.mapping);
    const std::string text = ros_bridge::direction_text(weakest.direction, weakest.sigma);
    status.add("weakest direction (sensor frame, LiDAR)", text);
    if (degenerate_state_.degenerate()) {
      const std::string holder =
          !weakest.degenerate ? " (fixed again on the last scan, not yet on enough in a row)"
          : weakest.held      ? ": held by " + weakest.held_by
                              : ": nothing holds it, the motion along it is a guess";
      status.raise(ros_bridge::HealthLevel::kWarn,
                   std::string("degenerate along ") + text + holder);
    }
  }
  if (mapping_->localizing()) {
    // The saved map's keyframes, as when it was made: this drive's own stay out of the map.
    const int map_keyframes = mapping_->map_keyframes();
    status.add("keyframes", std::to_string(map_keyframes));
    status.add("keyframes of this drive",
               std::to_string(mapping_->keyframes().size() - map_keyframes));
    status.add("map", map_folder_);
    const std::string state = last_state_ ? to_string(*last_state_) : "waiting for a scan";
    status.add("localization", state);
    status.add("scans lost (total)", std::to_string(lost_scans_));
    if (last_state_ == LocalizationState::kLost) {
      status.raise(ros_bridge::HealthLevel::kError, "localization lost");
    }
    return;
  }
  status.add("keyframes", std::to_string(mapping_->keyframes().size()));
  const LoopClosureCounts& loops = mapping_->loop_closure_counts();
  status.add("loops closed", std::to_string(mapping_->loops_closed()));
  status.add("loop candidates (place / radius)", std::to_string(loops.place_candidates) + " / " +
                                                     std::to_string(loops.radius_candidates));
  status.add("loops verified", std::to_string(loops.verified));
  status.add("loops rejected", std::to_string(loops.rejected));
  status.add("loops beyond the drift bound", std::to_string(loops.beyond_drift));
  status.add("loops unconfirmed", std::to_string(loops.unconfirmed));
  status.add("loops removed", std::to_string(loops.removed));
}

int run_map_optimization(int argc, char** argv) {
  return ros_bridge::run_node<MapOptimizationNode>(argc, argv, "map_optimization");
}

}  // namespace adaptive_lego_loam::nodes
