#include "adaptive_lego_loam/ros/motion_sensor_conversions.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

constexpr double kUnknownVariance = 1e6;

Eigen::Vector3d vector_of(const geometry_msgs::Vector3& v) {
  return Eigen::Vector3d(v.x, v.y, v.z);
}

void set_vector(geometry_msgs::Vector3& out, const Eigen::Vector3d& v) {
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
}

void set_diagonal(boost::array<double, 9>& covariance, double variance) {
  covariance.fill(0.0);
  covariance[0] = covariance[4] = covariance[8] = variance;
}

template <typename Message, typename Convert>
auto read_bag(const std::string& path, const std::string& topic, const char* expected_type,
              Convert convert) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw IoError(path + ": cannot open bag: " + e.what());
  }
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  if (view.size() == 0) throw IoError(path + ": no message on topic " + topic);
  std::vector<decltype(convert(std::declval<const Message&>()))> samples;
  samples.reserve(view.size());
  for (const rosbag::MessageInstance& message : view) {
    const auto msg = message.instantiate<Message>();
    if (!msg) {
      throw IoError(path + ": topic " + topic + " holds " + message.getDataType() +
                    ", expected " + expected_type);
    }
    samples.push_back(convert(*msg));
    if (msg->header.stamp.isZero()) samples.back().stamp = message.getTime().toSec();
  }
  return samples;
}

}  // namespace

ImuSample imu_from_ros(const sensor_msgs::Imu& msg) {
  ImuSample sample;
  sample.stamp = msg.header.stamp.toSec();
  sample.angular_velocity = vector_of(msg.angular_velocity);
  sample.linear_acceleration = vector_of(msg.linear_acceleration);
  return sample;
}

WheelOdometrySample wheel_odometry_from_ros(const nav_msgs::Odometry& msg) {
  WheelOdometrySample sample;
  sample.stamp = msg.header.stamp.toSec();
  sample.linear_velocity = vector_of(msg.twist.twist.linear);
  sample.angular_velocity = vector_of(msg.twist.twist.angular);
  // The 6 x 6 row-major covariance of (x, y, z, rotation about x, y, z).
  sample.linear_x_variance = msg.twist.covariance[0];
  sample.angular_z_variance = msg.twist.covariance[35];
  return sample;
}

sensor_msgs::Imu imu_to_ros(const ImuSample& sample, const std_msgs::Header& header,
                            double gyro_variance, double accel_variance) {
  sensor_msgs::Imu msg;
  msg.header = header;
  msg.orientation.w = 1.0;
  msg.orientation_covariance.fill(0.0);
  msg.orientation_covariance[0] = -1.0;
  set_vector(msg.angular_velocity, sample.angular_velocity);
  set_diagonal(msg.angular_velocity_covariance, gyro_variance);
  set_vector(msg.linear_acceleration, sample.linear_acceleration);
  set_diagonal(msg.linear_acceleration_covariance, accel_variance);
  return msg;
}

nav_msgs::Odometry wheel_odometry_to_ros(const WheelOdometrySample& sample,
                                         const Eigen::Isometry3d& pose,
                                         const std_msgs::Header& header,
                                         const std::string& child_frame) {
  nav_msgs::Odometry msg = odometry_to_ros(pose, header, child_frame);
  set_vector(msg.twist.twist.linear, sample.linear_velocity);
  set_vector(msg.twist.twist.angular, sample.angular_velocity);
  boost::array<double, 36>& twist = msg.twist.covariance;
  twist.fill(0.0);
  twist[0] = twist[7] = twist[14] = sample.linear_x_variance;
  twist[21] = twist[28] = kUnknownVariance;
  twist[35] = sample.angular_z_variance;
  return msg;
}

std::vector<ImuSample> read_bag_imu(const std::string& path, const std::string& topic) {
  return read_bag<sensor_msgs::Imu>(path, topic, "sensor_msgs/Imu", imu_from_ros);
}

std::vector<WheelOdometrySample> read_bag_wheel_odometry(const std::string& path,
                                                         const std::string& topic) {
  return read_bag<nav_msgs::Odometry>(path, topic, "nav_msgs/Odometry", wheel_odometry_from_ros);
}

}  // namespace adaptive_lego_loam::ros_bridge
