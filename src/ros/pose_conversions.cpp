#include "adaptive_lego_loam/ros/pose_conversions.h"

#include <tf2_eigen/tf2_eigen.h>

#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam::ros_bridge {

nav_msgs::Odometry odometry_to_ros(const Eigen::Isometry3d& pose, const std_msgs::Header& header,
                                   const std::string& child_frame) {
  nav_msgs::Odometry msg;
  msg.header = header;
  msg.child_frame_id = child_frame;
  msg.pose.pose = tf2::toMsg(pose);
  return msg;
}

namespace {

// Parent-frame [translation, rotation] from child-frame [rotation, translation] (orthonormal:
// its transpose goes back).
Eigen::Matrix<double, 6, 6> child_to_parent(const geometry_msgs::Quaternion& orientation) {
  const Eigen::Matrix3d rotation =
      Eigen::Quaterniond(orientation.w, orientation.x, orientation.y, orientation.z)
          .normalized()
          .toRotationMatrix();
  Eigen::Matrix<double, 6, 6> to_parent = Eigen::Matrix<double, 6, 6>::Zero();
  to_parent.topRightCorner<3, 3>() = rotation;
  to_parent.bottomLeftCorner<3, 3>() = rotation;
  return to_parent;
}

}  // namespace

void set_pose_covariance(const Eigen::Matrix<double, 6, 6>& covariance,
                         geometry_msgs::PoseWithCovariance& pose) {
  const Eigen::Matrix<double, 6, 6> to_parent = child_to_parent(pose.pose.orientation);
  const Eigen::Matrix<double, 6, 6> parent = to_parent * covariance * to_parent.transpose();
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col)
      pose.covariance[6 * row + col] = parent(row, col);
  }
}

Eigen::Matrix<double, 6, 6> pose_covariance_from_ros(const geometry_msgs::PoseWithCovariance& pose,
                                                     const std::string& source) {
  Eigen::Matrix<double, 6, 6> parent;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) {
      parent(row, col) = pose.covariance[6 * row + col];
      if (!std::isfinite(parent(row, col)))
        throw IoError(source + ": pose covariance holds a non-finite number");
    }
  }
  const Eigen::Matrix<double, 6, 6> to_parent = child_to_parent(pose.pose.orientation);
  return to_parent.transpose() * parent * to_parent;
}

Eigen::Isometry3d pose_from_ros(const geometry_msgs::Pose& pose, const std::string& source) {
  const geometry_msgs::Point& t = pose.position;
  const geometry_msgs::Quaternion& q = pose.orientation;
  for (double value : {t.x, t.y, t.z, q.x, q.y, q.z, q.w}) {
    if (!std::isfinite(value)) throw IoError(source + ": pose holds a non-finite number");
  }
  Eigen::Quaterniond rotation(q.w, q.x, q.y, q.z);
  if (rotation.norm() < 1e-9) throw IoError(source + ": pose has a zero quaternion");
  rotation.normalize();
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = rotation.toRotationMatrix();
  result.translation() = Eigen::Vector3d(t.x, t.y, t.z);
  return result;
}

geometry_msgs::Twist motion_to_twist(const Eigen::Isometry3d& motion, double dt) {
  const Eigen::AngleAxisd rotation(motion.rotation());
  const Eigen::Vector3d linear = motion.translation() / dt;
  const Eigen::Vector3d angular = rotation.axis() * (rotation.angle() / dt);
  geometry_msgs::Twist twist;
  twist.linear.x = linear.x();
  twist.linear.y = linear.y();
  twist.linear.z = linear.z();
  twist.angular.x = angular.x();
  twist.angular.y = angular.y();
  twist.angular.z = angular.z();
  return twist;
}

Eigen::Isometry3d motion_from_twist(const geometry_msgs::Twist& twist, double dt,
                                    const std::string& source) {
  const Eigen::Vector3d linear(twist.linear.x, twist.linear.y, twist.linear.z);
  const Eigen::Vector3d angular(twist.angular.x, twist.angular.y, twist.angular.z);
  if (!linear.allFinite() || !angular.allFinite()) {
    throw IoError(source + ": twist holds a non-finite number");
  }
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  const double angle = angular.norm() * dt;
  if (angle > 0.0) motion.linear() = Eigen::AngleAxisd(angle, angular.normalized()).matrix();
  motion.translation() = linear * dt;
  return motion;
}

geometry_msgs::TransformStamped transform_to_ros(const Eigen::Isometry3d& pose,
                                                 const std_msgs::Header& header,
                                                 const std::string& child_frame) {
  geometry_msgs::TransformStamped msg = tf2::eigenToTransform(pose);
  msg.header = header;
  msg.child_frame_id = child_frame;
  return msg;
}

nav_msgs::Path path_to_ros(const std::vector<Eigen::Isometry3d>& poses,
                           const std::vector<ros::Time>& stamps, const std::string& frame) {
  if (poses.size() != stamps.size()) {
    throw std::invalid_argument("path_to_ros: " + std::to_string(poses.size()) + " poses but " +
                                std::to_string(stamps.size()) + " stamps");
  }
  nav_msgs::Path path;
  path.header.frame_id = frame;
  if (!stamps.empty()) path.header.stamp = stamps.back();
  path.poses.resize(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    path.poses[i].header.frame_id = frame;
    path.poses[i].header.stamp = stamps[i];
    path.poses[i].pose = tf2::toMsg(poses[i]);
  }
  return path;
}

void mark_no_mapped_motion(nav_msgs::Odometry& msg) {
  msg.twist.covariance[0] = -1.0;
}

bool has_mapped_motion(const nav_msgs::Odometry& msg) {
  return msg.twist.covariance[0] >= 0.0;
}

}  // namespace adaptive_lego_loam::ros_bridge
