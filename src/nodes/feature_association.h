#pragma once
// feature_association: de-skewing, feature extraction and scan-to-scan odometry (LeGO-LOAM's
// featureAssociation) on image_projection's segmented cloud, cloud info and outlier cloud; with
// ~imu_topic or ~wheel_odom_topic also the motion sensors' stage (MotionSensors), whose
// prediction de-skews and guesses each scan and whose priors go to map_optimization.

#include <adaptive_lego_loam/MapMatch.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>

#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"
#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/ros/cloud_info_msg.h"
#include "adaptive_lego_loam/ros/motion_sensor_diagnostics.h"
#include "adaptive_lego_loam/ros/motion_sensor_relay.h"
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

  // A complete scan held until the motion sensors' samples up to its stamp came.
  struct PendingScan {
    ros_bridge::StampMatcher::Group group;
    double since_s;  // steady clock
  };

  void on_cloud(const sensor_msgs::PointCloud2ConstPtr& msg) { add(kCloud, msg->header, msg); }
  void on_info(const CloudInfoMsg::ConstPtr& msg) { add(kInfo, msg->header, msg); }
  void on_outliers(const sensor_msgs::PointCloud2ConstPtr& msg) {
    add(kOutliers, msg->header, msg);
  }
  void on_mapped(const nav_msgs::OdometryConstPtr& msg);
  void on_imu(const sensor_msgs::ImuConstPtr& msg);
  void on_wheel_odometry(const nav_msgs::OdometryConstPtr& msg);
  void on_map_match(const MapMatchConstPtr& msg);
  void add(Slot slot, const std_msgs::Header& header, ros_bridge::StampMatcher::Message msg);
  // Processes the held scans whose samples came or whose wait is over, oldest first.
  void release_pending();
  void process(const ros_bridge::StampMatcher::Group& group,
               ros_bridge::ScanRelease release = ros_bridge::ScanRelease::kReady);
  // The motion sensors' prediction of the scan (nullptr: LiDAR-only), with its time.
  const MotionPrediction* predict(const std_msgs::Header& header, ros_bridge::ScanRelease release,
                                  StageTimes& times);
  // The IMU's and the wheel's extrinsics from static TF, once each input has named its frame.
  void resolve_extrinsics(const std::string& sensor_frame);
  void drop(const std::string& reason, const std::string& detail);
  void reset();
  ros_bridge::SegmentedCloudTopics topics() const;
  void publish(const std_msgs::Header& header, const MotionPrediction* prediction);
  void add_diagnostics(ros_bridge::HealthStatus& status);
  void remember_weakest(const Observability& seen);

  Config config_;
  LidarOdometry odometry_;
  std::unique_ptr<Workers> workers_;  // ~threads: the searches shared (none: this thread)
  ros_bridge::ReceivedSegmentedCloud received_;  // the latest scan; its buffers are reused
  OdometryOutput out_;
  ros_bridge::FrameNames frames_;
  ros_bridge::ScanPairing pairing_;
  long pairing_dropped_ = 0;  // of pairing_.dropped() already counted
  // Implausible registrations whose prediction was kept (OdometryResult::rejected); the
  // diagnostics timer reads it.
  std::atomic<long> rejected_motions_{0};
  long rejected_motions_reported_ = 0;
  std::atomic<long> held_scans_{0};  // the follow test's (OdometryResult::held_direction)
  // The last registration's weakest direction (sensor frame) and sigma, for the diagnostics timer.
  std::mutex weakest_mutex_;
  std::string weakest_text_;
  std::optional<ros::Time> last_mapped_stamp_;
  ros_bridge::ThrottledWarning warn_;
  ros_bridge::StageSummary summary_;
  ros::Subscriber cloud_sub_, info_sub_, outlier_sub_, mapped_sub_;
  ros::Publisher corner_pub_, surface_pub_, outlier_pub_, odometry_pub_, sharp_pub_, flat_pub_;

  // The odometry's motion model is mapping's (uses_mapped_motion): from aft_mapped_to_init, or
  // with motion sensors from map_match.
  bool takes_mapped_motion_;
  // The motion sensors, with ~imu_topic or ~wheel_odom_topic only.
  std::optional<ros_bridge::MotionSensorRelay> relay_;
  std::deque<PendingScan> pending_;
  std::size_t max_pending_;
  double tf_wait_s_;
  // The frames the inputs' first messages name (the IMU's frame_id, the odometry's
  // child_frame_id or ~base_frame), and whether their extrinsics were looked up.
  std::optional<std::string> imu_frame_, wheel_frame_;
  bool imu_extrinsic_resolved_ = false, wheel_extrinsic_resolved_ = false;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  ros::Subscriber imu_sub_, wheel_sub_, map_match_sub_;
  ros::Publisher priors_pub_, gravity_pub_;
  ros::Publisher hold_pub_;  // /odometry_hold, with the follow test on only
  ros::SteadyTimer release_timer_;
  std::optional<ros_bridge::MotionSensorDiagnostics> sensor_diagnostics_;

  ros_bridge::NodeDiagnostics diagnostics_;
};

}  // namespace adaptive_lego_loam::nodes
