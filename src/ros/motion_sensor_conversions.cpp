#include "adaptive_lego_loam/ros/motion_sensor_conversions.h"

#include "adaptive_lego_loam/ros/pose_conversions.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

constexpr double kUnknownVariance = 1e6;

void set_diagonal(boost::array<double, 9>& covariance, double variance) {
  covariance.fill(0.0);
  covariance[0] = covariance[4] = covariance[8] = variance;
}

}  // namespace

sensor_msgs::Imu imu_to_ros(const ImuSample& sample, const std_msgs::Header& header,
                            double gyro_variance, double accel_variance) {
  sensor_msgs::Imu msg;
  msg.header = header;
  msg.orientation.w = 1.0;
  msg.orientation_covariance.fill(0.0);
  msg.orientation_covariance[0] = -1.0;
  msg.angular_velocity.x = sample.angular_velocity.x();
  msg.angular_velocity.y = sample.angular_velocity.y();
  msg.angular_velocity.z = sample.angular_velocity.z();
  set_diagonal(msg.angular_velocity_covariance, gyro_variance);
  msg.linear_acceleration.x = sample.linear_acceleration.x();
  msg.linear_acceleration.y = sample.linear_acceleration.y();
  msg.linear_acceleration.z = sample.linear_acceleration.z();
  set_diagonal(msg.linear_acceleration_covariance, accel_variance);
  return msg;
}

nav_msgs::Odometry wheel_odometry_to_ros(const WheelOdometrySample& sample,
                                         const Eigen::Isometry3d& pose,
                                         const std_msgs::Header& header,
                                         const std::string& child_frame) {
  nav_msgs::Odometry msg = odometry_to_ros(pose, header, child_frame);
  msg.twist.twist.linear.x = sample.linear_velocity.x();
  msg.twist.twist.linear.y = sample.linear_velocity.y();
  msg.twist.twist.linear.z = sample.linear_velocity.z();
  msg.twist.twist.angular.x = sample.angular_velocity.x();
  msg.twist.twist.angular.y = sample.angular_velocity.y();
  msg.twist.twist.angular.z = sample.angular_velocity.z();
  boost::array<double, 36>& twist = msg.twist.covariance;
  twist.fill(0.0);
  twist[0] = twist[7] = twist[14] = sample.linear_x_variance;
  twist[21] = twist[28] = kUnknownVariance;
  twist[35] = sample.angular_z_variance;
  return msg;
}

}  // namespace adaptive_lego_loam::ros_bridge
