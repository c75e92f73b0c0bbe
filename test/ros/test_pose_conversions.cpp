// Conversions of the nodes' messages: what image_projection sends feature_association, the
// feature clouds, poses, odometry and TF, and the degeneration state.

#include <gtest/gtest.h>

#include <sensor_msgs/point_cloud2_iterator.h>

#include <cmath>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"
#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/degeneration_conversions.h"
#include "adaptive_lego_loam/ros/feature_conversions.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/segmented_cloud_conversions.h"
#include "ros/filtered_scans.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
using namespace adaptive_lego_loam::ros_bridge;

namespace {

Eigen::Isometry3d sample_pose() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, -0.3, 1).normalized()).matrix();
  pose.translation() = Eigen::Vector3d(12.5, -3.25, 0.4);
  return pose;
}

}  // namespace

TEST(PoseConversions, OdometryRoundTripAndFrames) {
  const nav_msgs::Odometry msg = odometry_to_ros(sample_pose(), header_at(5.0, "odom"), "velodyne");
  EXPECT_EQ(msg.header.frame_id, "odom");
  EXPECT_EQ(msg.child_frame_id, "velodyne");
  EXPECT_DOUBLE_EQ(msg.pose.pose.position.x, 12.5);
  const Eigen::Isometry3d back = pose_from_ros(msg.pose.pose, "laser_odom_to_init");
  EXPECT_TRUE(back.isApprox(sample_pose(), 1e-14));
}

TEST(PoseConversions, CovarianceIsInTheParentsAxesTranslationFirst) {
  // The sensor turned 90 deg left: its own x is the map's y. Unsure 2 m along its x (a tunnel's
  // axis), 1 deg about its z.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  nav_msgs::Odometry msg = odometry_to_ros(pose, header_at(5.0, "map"), "velodyne");
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Identity() * 1e-6;
  covariance(3, 3) = 4.0;                              // the sensor's x
  covariance(2, 2) = std::pow(1.0 * M_PI / 180.0, 2);  // about the sensor's z
  set_pose_covariance(covariance, msg.pose);
  EXPECT_NEAR(msg.pose.covariance[6 * 1 + 1], 4.0, 1e-12);   // the map's y
  EXPECT_NEAR(msg.pose.covariance[6 * 0 + 0], 1e-6, 1e-12);  // the map's x
  EXPECT_NEAR(msg.pose.covariance[6 * 5 + 5], covariance(2, 2), 1e-12);
  EXPECT_NEAR(msg.pose.covariance[6 * 3 + 3], 1e-6, 1e-12);
}

TEST(PoseConversions, BadPosesAreRejectedNamingTheTopic) {
  geometry_msgs::Pose pose;  // zero quaternion
  EXPECT_THROW(pose_from_ros(pose, "/laser_odom_to_init"), IoError);
  pose.orientation.w = std::nan("");
  try {
    pose_from_ros(pose, "/laser_odom_to_init");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), "/laser_odom_to_init: pose holds a non-finite number");
  }
  pose.orientation.w = 2.0;  // not normalised: accepted, normalised
  EXPECT_TRUE(pose_from_ros(pose, "t").linear().isApprox(Eigen::Matrix3d::Identity(), 1e-15));
}

TEST(PoseConversions, TransformMovesChildPointsIntoTheParent) {
  const auto msg = transform_to_ros(sample_pose(), header_at(1.0, "map"), "odom");
  EXPECT_EQ(msg.header.frame_id, "map");
  EXPECT_EQ(msg.child_frame_id, "odom");
  EXPECT_DOUBLE_EQ(msg.transform.translation.y, -3.25);
  const Eigen::Quaterniond q(msg.transform.rotation.w, msg.transform.rotation.x,
                             msg.transform.rotation.y, msg.transform.rotation.z);
  EXPECT_TRUE(q.toRotationMatrix().isApprox(sample_pose().linear(), 1e-14));
}

TEST(PoseConversions, PathHoldsEveryPoseWithItsStamp) {
  const std::vector<Eigen::Isometry3d> poses = {Eigen::Isometry3d::Identity(), sample_pose()};
  const nav_msgs::Path path = path_to_ros(poses, {ros::Time(1.0), ros::Time(1.1)}, "map");
  ASSERT_EQ(path.poses.size(), 2u);
  EXPECT_EQ(path.header.frame_id, "map");
  EXPECT_EQ(path.header.stamp, ros::Time(1.1));
  EXPECT_EQ(path.poses[1].header.stamp, ros::Time(1.1));
  EXPECT_DOUBLE_EQ(path.poses[1].pose.position.z, 0.4);
  EXPECT_THROW(path_to_ros(poses, {ros::Time(1.0)}, "map"), std::invalid_argument);
}

TEST(PoseConversions, APoseCovarianceReadsBackAsWritten) {
  nav_msgs::Odometry msg;
  msg.pose.pose.orientation.z = std::sin(0.35);
  msg.pose.pose.orientation.w = std::cos(0.35);
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Identity() * 1e-4;
  covariance(3, 3) = 2.0;
  covariance(0, 4) = covariance(4, 0) = 3e-5;
  set_pose_covariance(covariance, msg.pose);
  EXPECT_TRUE(pose_covariance_from_ros(msg.pose, "t").isApprox(covariance, 1e-12));
  msg.pose.covariance[7] = std::nan("");
  try {
    pose_covariance_from_ros(msg.pose, "/laser_odom_to_init");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/laser_odom_to_init: pose covariance holds a non-finite number");
  }
}
