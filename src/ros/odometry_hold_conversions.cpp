#include "adaptive_lego_loam/ros/odometry_hold_conversions.h"

#include <cmath>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam::ros_bridge {

OdometryHold odometry_hold_to_ros(const OdometryResult& odometry, const std_msgs::Header& header) {
  OdometryHold msg;
  msg.header = header;
  msg.follow = odometry.follow;
  if (odometry.held_direction) {
    msg.held = true;
    msg.direction.x = odometry.held_direction->x();
    msg.direction.y = odometry.held_direction->y();
    msg.direction.z = odometry.held_direction->z();
  }
  return msg;
}

std::optional<Eigen::Vector3d> odometry_held_from_ros(const OdometryHold& msg,
                                                      const std::string& source) {
  if (!msg.held) return std::nullopt;
  const Eigen::Vector3d direction(msg.direction.x, msg.direction.y, msg.direction.z);
  if (!direction.allFinite() || std::abs(direction.norm() - 1.0) > 1e-6) {
    throw IoError(source + ": direction is not a unit vector (held is true)");
  }
  return direction;
}

}  // namespace adaptive_lego_loam::ros_bridge
