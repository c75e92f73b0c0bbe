#pragma once
// The motion sensors' samples and their ROS messages, both ways: sensor_msgs/Imu (angular velocity
// and linear acceleration; an orientation is neither read nor written) and nav_msgs/Odometry (the
// twist, in the frame of child_frame_id, with its covariance's forward-speed and yaw-rate
// variances); and all of one topic's samples from a bag, for the offline tools.

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/Imu.h>
#include <std_msgs/Header.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam::ros_bridge {

ImuSample imu_from_ros(const sensor_msgs::Imu& msg);
WheelOdometrySample wheel_odometry_from_ros(const nav_msgs::Odometry& msg);

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

// Every message of `topic` in the bag at `path`, in the bag's order, stamped with its header
// (when the header has no stamp, the time the bag recorded it). Throws IoError naming the bag and
// the topic when it cannot be opened, the topic has no message, or holds another type.
std::vector<ImuSample> read_bag_imu(const std::string& path, const std::string& topic);
std::vector<WheelOdometrySample> read_bag_wheel_odometry(const std::string& path,
                                                         const std::string& topic);

}  // namespace adaptive_lego_loam::ros_bridge
