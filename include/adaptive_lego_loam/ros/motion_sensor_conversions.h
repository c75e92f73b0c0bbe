#pragma once
// The motion sensors' samples as ROS messages: sensor_msgs/Imu and nav_msgs/Odometry.

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/Header.h>

#include <Eigen/Geometry>
#include <string>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam::ros_bridge {

// An IMU without an orientation estimate (orientation_covariance[0] = -1, as sensor_msgs/Imu
// says), the variances on its covariances' diagonals. The sample's stamp is not used: the
// header holds the message's.
sensor_msgs::Imu imu_to_ros(const ImuSample& sample, const std_msgs::Header& header,
                            double gyro_variance, double accel_variance);

// A wheel odometry's message: `pose` the base frame's pose in header.frame_id (as the driver
// integrated it), the twist in `child_frame` with the sample's variances (forward speed and
// yaw rate; sideways and vertical speed as the forward one, roll and pitch rates unknown: 1e6).
nav_msgs::Odometry wheel_odometry_to_ros(const WheelOdometrySample& sample,
                                         const Eigen::Isometry3d& pose,
                                         const std_msgs::Header& header,
                                         const std::string& child_frame);

}  // namespace adaptive_lego_loam::ros_bridge
