// The motion sensors' samples as sensor_msgs/Imu and nav_msgs/Odometry.

#include <gtest/gtest.h>

#include "adaptive_lego_loam/ros/motion_sensor_conversions.h"

using namespace adaptive_lego_loam;

TEST(MotionSensorConversions, AnImuWithoutOrientation) {
  ImuSample sample;
  sample.angular_velocity = Eigen::Vector3d(0.1, -0.2, 0.3);
  sample.linear_acceleration = Eigen::Vector3d(0.5, 0.0, 9.81);
  std_msgs::Header header;
  header.frame_id = "imu";
  header.stamp.fromSec(1e9 + 2.5);
  const sensor_msgs::Imu msg = ros_bridge::imu_to_ros(sample, header, 1e-6, 4e-4);
  EXPECT_EQ(msg.header.frame_id, "imu");
  EXPECT_EQ(msg.orientation_covariance[0], -1.0);
  EXPECT_EQ(msg.angular_velocity.y, -0.2);
  EXPECT_EQ(msg.linear_acceleration.z, 9.81);
  EXPECT_EQ(msg.angular_velocity_covariance[4], 1e-6);
  EXPECT_EQ(msg.linear_acceleration_covariance[8], 4e-4);
  EXPECT_EQ(msg.linear_acceleration_covariance[1], 0.0);
}

TEST(MotionSensorConversions, AWheelOdometrysTwistAndPose) {
  WheelOdometrySample sample;
  sample.linear_velocity.x() = 7.5;
  sample.angular_velocity.z() = -0.1;
  sample.linear_x_variance = 0.0025;
  sample.angular_z_variance = 0.0004;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(3.0, 1.0, 0.0);
  std_msgs::Header header;
  header.frame_id = "odom";
  const nav_msgs::Odometry msg =
      ros_bridge::wheel_odometry_to_ros(sample, pose, header, "base_link");
  EXPECT_EQ(msg.child_frame_id, "base_link");
  EXPECT_EQ(msg.pose.pose.position.x, 3.0);
  EXPECT_EQ(msg.twist.twist.linear.x, 7.5);
  EXPECT_EQ(msg.twist.twist.angular.z, -0.1);
  EXPECT_EQ(msg.twist.covariance[0], 0.0025);
  EXPECT_EQ(msg.twist.covariance[35], 0.0004);
  EXPECT_GT(msg.twist.covariance[21], 1e3);  // roll rate unknown
}

TEST(MotionSensorConversions, MessagesBackToSamplesAreExact) {
  ImuSample imu;
  imu.angular_velocity = Eigen::Vector3d(0.1, -0.2, 0.3);
  imu.linear_acceleration = Eigen::Vector3d(0.5, 0.0, 9.81);
  std_msgs::Header header;
  header.stamp.fromSec(1e9 + 2.5);
  const ImuSample imu_back = ros_bridge::imu_from_ros(ros_bridge::imu_to_ros(imu, header, 0, 0));
  EXPECT_DOUBLE_EQ(imu_back.stamp, 1e9 + 2.5);
  EXPECT_EQ(imu_back.angular_velocity, imu.angular_velocity);
  EXPECT_EQ(imu_back.linear_acceleration, imu.linear_acceleration);
  WheelOdometrySample wheel;
  wheel.linear_velocity.x() = 7.5;
  wheel.angular_velocity.z() = -0.1;
  wheel.linear_x_variance = 0.0025;
  wheel.angular_z_variance = 0.0004;
  const WheelOdometrySample wheel_back = ros_bridge::wheel_odometry_from_ros(
      ros_bridge::wheel_odometry_to_ros(wheel, Eigen::Isometry3d::Identity(), header, "base"));
  EXPECT_EQ(wheel_back.linear_velocity, wheel.linear_velocity);
  EXPECT_EQ(wheel_back.angular_velocity, wheel.angular_velocity);
  EXPECT_EQ(wheel_back.linear_x_variance, 0.0025);
  EXPECT_EQ(wheel_back.angular_z_variance, 0.0004);
}
