#include <gtest/gtest.h>

#include <sensor_msgs/point_cloud2_iterator.h>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"

using namespace adaptive_lego_loam;

TEST(CloudConversions, RoundTripWithRingAndTime) {
  std::vector<ScanPoint> points(3);
  for (int i = 0; i < 3; ++i)
    points[i] = {float(i), float(2 * i), float(-i), 0.5f, 0.01f * i, i + 4};
  std_msgs::Header header;
  header.stamp.fromSec(12.5);
  const auto msg = ros_bridge::to_ros(points, header, true);
  const Scan scan = ros_bridge::from_ros(msg, "/velodyne_points");
  ASSERT_EQ(scan.points.size(), 3u);
  EXPECT_TRUE(scan.has_ring);
  EXPECT_TRUE(scan.has_time);
  EXPECT_DOUBLE_EQ(scan.stamp, 12.5);
  EXPECT_EQ(scan.points[2].ring, 6);
  EXPECT_FLOAT_EQ(scan.points[2].time, 0.02f);
  EXPECT_FLOAT_EQ(scan.points[1].y, 2.f);
}

TEST(CloudConversions, WithoutRingAndTime) {
  const auto msg = ros_bridge::to_ros({{1, 2, 3, 4}}, std_msgs::Header(), false);
  const Scan scan = ros_bridge::from_ros(msg, "/velodyne_points");
  ASSERT_EQ(scan.points.size(), 1u);
  EXPECT_FALSE(scan.has_ring);
  EXPECT_FALSE(scan.has_time);
  EXPECT_FLOAT_EQ(scan.points[0].intensity, 4.f);
}

TEST(CloudConversions, OusterStyleNanosecondTimeAndDoubleCoordinates) {
  sensor_msgs::PointCloud2 msg;
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2Fields(
      4, "x", 1, sensor_msgs::PointField::FLOAT64, "y", 1, sensor_msgs::PointField::FLOAT64, "z", 1,
      sensor_msgs::PointField::FLOAT64, "t", 1, sensor_msgs::PointField::UINT32);
  modifier.resize(1);
  sensor_msgs::PointCloud2Iterator<double> x(msg, "x");
  *x = 7.0;
  sensor_msgs::PointCloud2Iterator<uint32_t> t(msg, "t");
  *t = 25000000;
  const Scan scan = ros_bridge::from_ros(msg, "/os_cloud_node/points");
  EXPECT_FLOAT_EQ(scan.points[0].x, 7.f);
  EXPECT_FLOAT_EQ(scan.points[0].time, 0.025f);
}

TEST(CloudConversions, MissingFieldNamesTopic) {
  sensor_msgs::PointCloud2 msg;
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2Fields(2, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1,
                                sensor_msgs::PointField::FLOAT32);
  modifier.resize(1);
  try {
    ros_bridge::from_ros(msg, "/velodyne_points");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/velodyne_points: missing field z"), std::string::npos)
        << e.what();
  }
}
