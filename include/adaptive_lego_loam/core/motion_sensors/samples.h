#pragma once
// The optional motion sensors as the core sees them: an IMU's samples and a wheel odometry's
// twists, plain values with their stamps on the scans' clock. No ROS.

#include <Eigen/Core>

namespace adaptive_lego_loam {

struct ImuSample {
  double stamp = 0.0;                                          // s
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, IMU frame
  // Specific force, m/s^2, IMU frame: at rest an IMU reads +g along its up axis (as
  // sensor_msgs/Imu's linear_acceleration).
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();
};

// A wheel odometry's twist of the vehicle's base frame, in that frame (as nav_msgs/Odometry's
// twist with child_frame_id the base).
struct WheelOdometrySample {
  double stamp = 0.0;                                          // s
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // m/s
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s
  // Variances of the forward speed, (m/s)^2, and of the yaw rate, (rad/s)^2, as the source
  // reports them; 0: not reported (the config's defaults then hold).
  double linear_x_variance = 0.0;
  double angular_z_variance = 0.0;
};

}  // namespace adaptive_lego_loam
