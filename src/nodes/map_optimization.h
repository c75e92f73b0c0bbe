#pragma once
// map_optimization: scan-to-map matching against the local map of keyframes (LeGO-LOAM's
// mapOptimization) on feature_association's features and odometry, with loop closure; or, given
// ~map, localization on a saved map. Publishes the mapped pose, the map -> odom correction as TF,
// the keyframe positions, the path and the local map; serves save_map.

#include <adaptive_lego_loam/DegenerationState.h>
#include <adaptive_lego_loam/MotionPriors.h>
#include <adaptive_lego_loam/OdometryHold.h>
#include <adaptive_lego_loam/SaveMap.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/pipeline/degeneracy_tracker.h"
#include "adaptive_lego_loam/core/pipeline/lidar_mapping.h"
#include "adaptive_lego_loam/io/process_memory.h"
#include "adaptive_lego_loam/ros/node_config.h"
#include "adaptive_lego_loam/ros/node_diagnostics.h"
#include "adaptive_lego_loam/ros/node_logging.h"
#include "adaptive_lego_loam/ros/stamp_matcher.h"

namespace adaptive_lego_loam::nodes {

class MapOptimizationNode {
 public:
  MapOptimizationNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const Config& config);
  // Saves the map to ~save_map_on_exit, when set.
  ~MapOptimizationNode();

 private:
  // /degeneration is paired with every scan: the scene's weak direction and mu weigh the
  // weak-direction prior, the motion sensors' priors and the pose's covariance. /motion_priors
  // only with motion sensors, /odometry_hold only with the follow test, in that order after the
  // fixed slots.
  enum Slot : std::size_t { kCorners, kSurfaces, kOutliers, kOdometry, kDegeneration };
  std::size_t priors_slot() const { return kDegeneration + 1; }
  std::size_t hold_slot() const { return kDegeneration + 1 + uses_motion_sensors_; }

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
  void on_motion_priors(const MotionPriorsConstPtr& msg) { add(priors_slot(), msg->header, msg); }
  void on_odometry_hold(const OdometryHoldConstPtr& msg) { add(hold_slot(), msg->header, msg); }
  void on_initial_pose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg);
  bool on_save_map(SaveMap::Request& request, SaveMap::Response& response);

  void add(std::size_t slot, const std_msgs::Header& header, ros_bridge::StampMatcher::Message msg);
  void process(const ros_bridge::StampMatcher::Group& group);
  void map_scan(const ros_bridge::StampMatcher::Group& group);
  std::string topic(std::size_t slot) const { return subscriptions_[slot].getTopic(); }
  void log_loop(const LoopDetection& loop) const;
  void log_localization(const LocalizationStatus& status);
  void publish(const ros::Time& stamp);
  // The keyframes (loop closures bend it) or, localizing, the drive's poses a metre apart, and
  // the newest pose: it grows with the ground covered, not with time.
  nav_msgs::Path path(const ros::Time& stamp) const;
  void add_diagnostics(ros_bridge::HealthStatus& status) const;
  std::unique_ptr<LidarMapping> make_mapping() const;
  struct Saved {
    std::string message;  // the folder and the keyframe count
    int keyframes = 0;
  };
  // Writes the map (throws IoError when it cannot).
  Saved save(const std::string& folder, double voxel_size);

  Config config_;
  std::string map_folder_;               // ~map: localization on this saved map
  std::vector<Keyframe> map_keyframes_;  // ... its keyframes, to start over from
  Eigen::Isometry3d initial_pose_ = Eigen::Isometry3d::Identity();  // ~initial_pose, /initialpose
  std::string save_on_exit_;                                        // ~save_map_on_exit
  mutable std::mutex mapping_mutex_;  // the mapping, between scans and save_map
  std::unique_ptr<LidarMapping> mapping_;
  std::unique_ptr<Workers> workers_;  // ~threads: the searches shared (none: this thread)
  MappingOutput out_;
  bool uses_motion_sensors_;  // ~motion_sensors: feature_association sends /motion_priors
  bool uses_odometry_hold_;   // the follow test: feature_association sends /odometry_hold
  std::optional<SceneDegeneration> scene_;  // the scan being mapped's, from /degeneration
  DegeneracyTracker degenerate_state_;      // what /diagnostics says, with hysteresis
  ros_bridge::FrameNames frames_;
  std::string sensor_frame_;
  long mapped_scans_ = 0;
  // rviz's path when localizing: this drive's poses, one a metre, the newest kPathPoses to
  // 2 kPathPoses of them (the keyframes when mapping).
  static constexpr std::size_t kPathPoses = 10000;
  std::vector<Eigen::Isometry3d> drive_poses_;
  std::vector<ros::Time> drive_stamps_;
  std::optional<ros::Time> last_stamp_;
  std::optional<LocalizationState> last_state_;
  long lost_scans_ = 0;  // localization: scans mapped while lost
  ros_bridge::ScanPairing pairing_;
  long pairing_dropped_ = 0;
  ros_bridge::Throttle surround_throttle_, path_throttle_;  // both grow with the map: throttled
  ros_bridge::ThrottledWarning warn_;
  ros_bridge::StageSummary summary_;
  std::vector<ros::Subscriber> subscriptions_;  // in Slot order
  ros::Subscriber initial_pose_sub_;
  ros::Publisher mapped_pub_, surround_pub_, keyframe_pub_, path_pub_, map_match_pub_,
      uncertainty_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros_bridge::NodeDiagnostics diagnostics_;
  HeapTrimmer heap_trimmer_;  // in a nodelet manager, for every stage in it
  // save_map runs on its own thread: a save does not hold up the scans.
  ros::CallbackQueue service_queue_;
  ros::ServiceServer save_service_;
  std::unique_ptr<ros::AsyncSpinner> service_spinner_;
};

}  // namespace adaptive_lego_loam::nodes
