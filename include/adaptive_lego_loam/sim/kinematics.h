#pragma once
// A moving frame's pose with its first and second time derivatives, and how they compose: what
// an IMU reads and a wheel odometry reports is the kinematics of their frames.

#include <Eigen/Geometry>

namespace adaptive_lego_loam::sim {

// The frame's pose in a reference frame, the velocity and acceleration of its origin in that
// reference frame, and its angular velocity and acceleration in its own axes.
struct Kinematics {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_acceleration = Eigen::Vector3d::Zero();

  // The velocity in the frame's own axes.
  Eigen::Vector3d body_velocity() const { return pose.linear().transpose() * velocity; }
};

// The motion of `child` (its kinematics relative to `parent`'s frame) seen from the parent's
// reference frame: pose parent.pose * child.pose, with the Coriolis, centripetal and Euler terms.
Kinematics compose(const Kinematics& parent, const Kinematics& child);

// A frame rigidly mounted on `body` at `body_from_frame` (its pose in the body frame).
Kinematics mounted(const Kinematics& body, const Eigen::Isometry3d& body_from_frame);

}  // namespace adaptive_lego_loam::sim
