#include "adaptive_lego_loam/ros/motion_sensor_conversions.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

Eigen::Vector3d vector_of(const geometry_msgs::Vector3& v) {
  return Eigen::Vector3d(v.x, v.y, v.z);
}

template <typename Message, typename Sample>
std::vector<Sample> read_bag(const std::string& path, const std::string& topic,
                             const char* expected_type) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw IoError(path + ": cannot open bag: " + e.what());
  }
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  if (view.size() == 0) throw IoError(path + ": no message on topic " + topic);
  std::vector<Sample> samples;
  samples.reserve(view.size());
  for (const rosbag::MessageInstance& message : view) {
    const auto msg = message.instantiate<Message>();
    if (!msg) {
      throw IoError(path + ": topic " + topic + " holds " + message.getDataType() +
                    ", expected " + expected_type);
    }
    Sample sample = from_ros(*msg);
    if (msg->header.stamp.isZero()) sample.stamp = message.getTime().toSec();
    samples.push_back(sample);
  }
  return samples;
}

}  // namespace

ImuSample from_ros(const sensor_msgs::Imu& msg) {
  ImuSample sample;
  sample.stamp = msg.header.stamp.toSec();
  sample.angular_velocity = vector_of(msg.angular_velocity);
  sample.linear_acceleration = vector_of(msg.linear_acceleration);
  return sample;
}

WheelOdometrySample from_ros(const nav_msgs::Odometry& msg) {
  WheelOdometrySample sample;
  sample.stamp = msg.header.stamp.toSec();
  sample.linear_velocity = vector_of(msg.twist.twist.linear);
  sample.angular_velocity = vector_of(msg.twist.twist.angular);
  // The 6 x 6 row-major covariance of (x, y, z, rotation about x, y, z).
  sample.linear_x_variance = msg.twist.covariance[0];
  sample.angular_z_variance = msg.twist.covariance[35];
  return sample;
}

std::vector<ImuSample> read_bag_imu(const std::string& path, const std::string& topic) {
  return read_bag<sensor_msgs::Imu, ImuSample>(path, topic, "sensor_msgs/Imu");
}

std::vector<WheelOdometrySample> read_bag_wheel_odometry(const std::string& path,
                                                         const std::string& topic) {
  return read_bag<nav_msgs::Odometry, WheelOdometrySample>(path, topic, "nav_msgs/Odometry");
}

}  // namespace adaptive_lego_loam::ros_bridge
