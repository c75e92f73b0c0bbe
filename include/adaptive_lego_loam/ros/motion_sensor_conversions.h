#pragma once
// The motion sensors' messages as the core's samples: sensor_msgs/Imu (angular velocity and
// linear acceleration; its orientation is not used) and nav_msgs/Odometry (the twist, in the
// frame of child_frame_id, with its covariance's forward-speed and yaw-rate variances); and all
// of one topic's samples from a bag, for the offline tools.

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/Imu.h>

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam::ros_bridge {

ImuSample from_ros(const sensor_msgs::Imu& msg);
WheelOdometrySample from_ros(const nav_msgs::Odometry& msg);

// Every message of `topic` in the bag at `path`, in the bag's order, stamped with its header
// (when the header has no stamp, the time the bag recorded it). Throws IoError naming the bag and
// the topic when it cannot be opened, the topic has no message, or holds another type.
std::vector<ImuSample> read_bag_imu(const std::string& path, const std::string& topic);
std::vector<WheelOdometrySample> read_bag_wheel_odometry(const std::string& path,
                                                         const std::string& topic);

}  // namespace adaptive_lego_loam::ros_bridge
