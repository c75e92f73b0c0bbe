#include "adaptive_lego_loam/sim/kinematics.h"

namespace adaptive_lego_loam::sim {

Kinematics compose(const Kinematics& parent, const Kinematics& child) {
  const Eigen::Matrix3d& parent_rotation = parent.pose.linear();
  const Eigen::Matrix3d child_rotation_inverse = child.pose.linear().transpose();
  const Eigen::Vector3d& offset = child.pose.translation();
  const Eigen::Vector3d& w = parent.angular_velocity;
  Kinematics out;
  out.pose = parent.pose * child.pose;
  out.velocity = parent.velocity + parent_rotation * (w.cross(offset) + child.velocity);
  out.acceleration =
      parent.acceleration +
      parent_rotation * (parent.angular_acceleration.cross(offset) + w.cross(w.cross(offset)) +
                         2.0 * w.cross(child.velocity) + child.acceleration);
  const Eigen::Vector3d parent_rate_in_child = child_rotation_inverse * w;
  out.angular_velocity = parent_rate_in_child + child.angular_velocity;
  out.angular_acceleration = child_rotation_inverse * parent.angular_acceleration -
                             child.angular_velocity.cross(parent_rate_in_child) +
                             child.angular_acceleration;
  return out;
}

Kinematics mounted(const Kinematics& body, const Eigen::Isometry3d& body_from_frame) {
  Kinematics fixed;
  fixed.pose = body_from_frame;
  return compose(body, fixed);
}

}  // namespace adaptive_lego_loam::sim
