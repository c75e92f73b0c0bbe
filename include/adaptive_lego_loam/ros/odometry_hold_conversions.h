#pragma once
// The odometry's follow test of a scan as a message (adaptive_lego_loam/OdometryHold,
// feature_association -> map_optimization): the direction scan-to-scan held at its guess, which
// scan-to-map holds too (LidarMapping::process's `odometry_held`).

#include <adaptive_lego_loam/OdometryHold.h>
#include <std_msgs/Header.h>

#include <Eigen/Core>
#include <optional>
#include <string>

#include "adaptive_lego_loam/core/odometry/scan_to_scan.h"

namespace adaptive_lego_loam::ros_bridge {

OdometryHold odometry_hold_to_ros(const OdometryResult& odometry, const std_msgs::Header& header);
// The held direction, exact (none when the scan was not held). Throws IoError naming `source`
// when a held direction is not a finite unit vector.
std::optional<Eigen::Vector3d> odometry_held_from_ros(const OdometryHold& msg,
                                                      const std::string& source);

}  // namespace adaptive_lego_loam::ros_bridge
