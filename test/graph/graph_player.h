#pragma once
// What the graph rostests' checkers share: the Player that plays messages into the graph in lock
// step on /clock and records what comes out (poses, warnings, /diagnostics), and waiting for the
// graph's topics and for conditions while the callbacks run.

#include <adaptive_lego_loam/DegenerationState.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/Marker.h>

#include <Eigen/Geometry>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/ros/pose_conversions.h"

namespace adaptive_lego_loam::graph_test {

// What the checker saw on the graph's outputs.
struct Recording {
  std::map<ros::Time, Eigen::Isometry3d> mapped, integrated;
  // Each pose's covariance as published (nav_msgs/Odometry's: parent-frame axes).
  using Covariance = Eigen::Matrix<double, 6, 6>;
  std::map<ros::Time, Covariance> odometry_covariance, mapped_covariance, integrated_covariance;
  std::map<ros::Time, std::string> mapped_child_frame;
  std::map<ros::Time, DegenerationState> degeneration;
  std::vector<std::string> image_projection_warnings;
  std::vector<std::string> time_jump_warnings;  // "time went back", from any stage
  std::vector<std::string> warnings;            // every warning, from any stage
  std::vector<std::string> infos;               // every info line, from any stage
  // The newest status of each name on /diagnostics ("image_projection: scans", ...).
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diagnostics;
  std::vector<diagnostic_msgs::DiagnosticStatus> diagnostics_history;  // every status, in order
  std::map<ros::Time, visualization_msgs::Marker> gravity_markers;     // record_gravity_markers()
  std::optional<Eigen::Isometry3d> tf_map_to_sensor;                   // at the last scan's stamp
  bool every_scan_mapped = true;
};

// Polls callbacks until `done` or `seconds` of wall time pass.
inline bool wait_for(const std::function<bool()>& done, double seconds) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    ros::spinOnce();
    if (done()) return true;
    ros::WallDuration(0.005).sleep();
  }
  return done();
}

// The nodes the master lists as publishers (kind 0) or subscribers (kind 1) of `topic`.
inline std::vector<std::string> registered_nodes(int kind, const std::string& topic) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  std::vector<std::string> nodes;
  if (!ros::master::execute("getSystemState", request, response, payload, false)) return nodes;
  for (int i = 0; i < payload[kind].size(); ++i) {
    if (std::string(payload[kind][i][0]) != topic) continue;
    for (int j = 0; j < payload[kind][i][1].size(); ++j)
      nodes.push_back(payload[kind][i][1][j]);
  }
  return nodes;
}

// Whether every topic has a publisher and a subscriber registered with the master.
inline bool graph_connected(const std::vector<std::string>& topics) {
  for (const std::string& topic : topics) {
    if (registered_nodes(0, topic).empty() || registered_nodes(1, topic).empty()) return false;
  }
  return true;
}

inline Eigen::Isometry3d pose_of(const nav_msgs::Odometry& msg) {
  return ros_bridge::pose_from_ros(msg.pose.pose, "test");
}

inline Recording::Covariance covariance_of(const nav_msgs::Odometry& msg) {
  return Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(msg.pose.covariance.data());
}

// A /diagnostics status's key-value pairs.
inline std::map<std::string, std::string> values_of(
    const diagnostic_msgs::DiagnosticStatus& status) {
  std::map<std::string, std::string> values;
  for (const auto& entry : status.values)
    values[entry.key] = entry.value;
  return values;
}

class Player {
 public:
  explicit Player(Recording& recording) : recording_(recording), tf_listener_(tf_buffer_) {
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    initial_pose_pub_ = nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("/initialpose", 1);
    cloud_pub_ = nh_.advertise<sensor_msgs::PointCloud2>("/velodyne_points", 10);
    subs_.push_back(nh_.subscribe<nav_msgs::Odometry>(
        "/aft_mapped_to_init", 10, [this](const nav_msgs::OdometryConstPtr& m) {
          recording_.mapped[m->header.stamp] = pose_of(*m);
          recording_.mapped_covariance[m->header.stamp] = covariance_of(*m);
          recording_.mapped_child_frame[m->header.stamp] = m->child_frame_id;
        }));
    subs_.push_back(nh_.subscribe<nav_msgs::Odometry>(
        "/integrated_to_init", 10, [this](const nav_msgs::OdometryConstPtr& m) {
          recording_.integrated[m->header.stamp] = pose_of(*m);
          recording_.integrated_covariance[m->header.stamp] = covariance_of(*m);
        }));
    subs_.push_back(nh_.subscribe<nav_msgs::Odometry>(
        "/laser_odom_to_init", 10, [this](const nav_msgs::OdometryConstPtr& m) {
          recording_.odometry_covariance[m->header.stamp] = covariance_of(*m);
        }));
    subs_.push_back(nh_.subscribe<DegenerationState>(
        "/degeneration", 10, [this](const DegenerationStateConstPtr& m) {
          recording_.degeneration[m->header.stamp] = *m;
        }));
    // Matched by the message's prefix: a nodelet logs under its manager's node name.
    subs_.push_back(nh_.subscribe<rosgraph_msgs::Log>(
        "/rosout", 100, [this](const rosgraph_msgs::LogConstPtr& m) {
          if (m->level == rosgraph_msgs::Log::INFO) recording_.infos.push_back(m->msg);
          if (m->level != rosgraph_msgs::Log::WARN) return;
          recording_.warnings.push_back(m->msg);
          if (m->msg.rfind("image_projection:", 0) == 0) {
            recording_.image_projection_warnings.push_back(m->msg);
          }
          if (m->msg.find("time went back") != std::string::npos) {
            recording_.time_jump_warnings.push_back(m->msg);
          }
        }));
    subs_.push_back(nh_.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArrayConstPtr& m) {
          for (const auto& status : m->status) {
            recording_.diagnostics[status.name] = status;
            recording_.diagnostics_history.push_back(status);
          }
        }));
  }

  // Waits until the status `name` on /diagnostics has `key` = `value`.
  bool wait_for_diagnostic(const std::string& name, const std::string& key,
                           const std::string& value) {
    return wait_for(
        [&] {
          const auto it = recording_.diagnostics.find(name);
          if (it == recording_.diagnostics.end()) return false;
          const auto values = values_of(it->second);
          const auto entry = values.find(key);
          return entry != values.end() && entry->second == value;
        },
        10.0);
  }

  // The IMU's and the wheel odometry's messages and the static transforms to the graph (the
  // motion sensors' test).
  void advertise_motion_sensors(const std::string& imu_topic, const std::string& odom_topic) {
    imu_pub_ = nh_.advertise<sensor_msgs::Imu>(imu_topic, 2000);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>(odom_topic, 500);
    tf_static_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf_static", 1, true);
  }
  void send_static_transforms(const tf2_msgs::TFMessage& msg) { tf_static_pub_.publish(msg); }
  void send_imu(const sensor_msgs::Imu& msg) { imu_pub_.publish(msg); }
  void send_odometry(const nav_msgs::Odometry& msg) { odom_pub_.publish(msg); }

  // Subscribes feature_association's gravity arrow (published only while subscribed).
  void record_gravity_markers() {
    subs_.push_back(nh_.subscribe<visualization_msgs::Marker>(
        "/gravity_marker", 100, [this](const visualization_msgs::MarkerConstPtr& m) {
          recording_.gravity_markers[m->header.stamp] = *m;
        }));
  }

  // Waits until every topic of the graph (and `extra_topics`) has a publisher and a subscriber,
  // and this checker's publishers are connected.
  bool wait_for_graph(const std::vector<std::string>& extra_topics = {}) {
    std::vector<std::string> topics = {"/velodyne_points",
                                       "/segmented_cloud",
                                       "/segmented_cloud_info",
                                       "/outlier_cloud",
                                       "/laser_cloud_corner_last",
                                       "/laser_cloud_surf_last",
                                       "/outlier_cloud_last",
                                       "/laser_odom_to_init",
                                       "/aft_mapped_to_init",
                                       "/integrated_to_init",
                                       "/degeneration"};
    topics.insert(topics.end(), extra_topics.begin(), extra_topics.end());
    if (!wait_for([&] { return graph_connected(topics); }, 60.0)) return false;
    // Registered is not yet connected: wait for this checker's own links, then give the stages'
    // links among themselves as long again (rosbag play -d does the same by time alone).
    const ros::WallTime registered = ros::WallTime::now();
    const auto connected = [](const ros::Publisher& publisher) {
      return !publisher || publisher.getNumSubscribers() > 0;
    };
    if (!wait_for(
            [&] { return connected(cloud_pub_) && connected(imu_pub_) && connected(odom_pub_); },
            30.0)) {
      return false;
    }
    ros::WallDuration(std::max(1.0, (ros::WallTime::now() - registered).toSec())).sleep();
    return true;
  }

  void send(const sensor_msgs::PointCloud2& cloud) {
    rosgraph_msgs::Clock clock;
    clock.clock = cloud.header.stamp;
    clock_pub_.publish(clock);
    cloud_pub_.publish(cloud);
  }

  // Sends a scan and waits until it is mapped and fused.
  bool play(const sensor_msgs::PointCloud2& cloud) {
    send(cloud);
    return wait_until_mapped(cloud.header.stamp);
  }

  // Waits until the scan at `stamp` is mapped and fused.
  bool wait_until_mapped(const ros::Time& stamp) {
    return wait_for(
        [&] { return recording_.mapped.count(stamp) && recording_.integrated.count(stamp); }, 30.0);
  }

  bool wait_for_warning(const std::string& text) {
    return wait_for_line(recording_.warnings, text);
  }
  bool wait_for_info(const std::string& text) { return wait_for_line(recording_.infos, text); }

  // Waits until a line of `lines` holds `text`.
  bool wait_for_line(const std::vector<std::string>& lines, const std::string& text) {
    return wait_for(
        [&] {
          for (const std::string& line : lines) {
            if (line.find(text) != std::string::npos) return true;
          }
          return false;
        },
        10.0);
  }

  // As rviz's "2D Pose Estimate" sends it, in `frame`.
  bool send_initial_pose(const Eigen::Isometry3d& pose, const std::string& frame) {
    if (!wait_for([&] { return initial_pose_pub_.getNumSubscribers() > 0; }, 10.0)) return false;
    geometry_msgs::PoseWithCovarianceStamped msg;
    msg.header.frame_id = frame;
    msg.header.stamp = ros::Time::now();
    msg.pose.pose = tf2::toMsg(pose);
    initial_pose_pub_.publish(msg);
    return true;
  }

  std::optional<Eigen::Isometry3d> lookup(const std::string& target, const std::string& source,
                                          const ros::Time& stamp) {
    if (!wait_for([&] { return tf_buffer_.canTransform(target, source, stamp); }, 10.0)) {
      return std::nullopt;
    }
    return tf2::transformToEigen(tf_buffer_.lookupTransform(target, source, stamp));
  }

 private:
  Recording& recording_;
  ros::NodeHandle nh_;
  ros::Publisher clock_pub_, cloud_pub_, initial_pose_pub_, imu_pub_, odom_pub_, tf_static_pub_;
  std::vector<ros::Subscriber> subs_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
};

inline double angle_between(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

}  // namespace adaptive_lego_loam::graph_test
