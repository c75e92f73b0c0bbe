// rviz's view of how well the mapped pose is known: the bar lies along the least-known direction,
// 3 sigma to either side (capped), its colour says whether the LiDAR fixes it, and the text says
// how far.

#include <gtest/gtest.h>

#include "adaptive_lego_loam/ros/uncertainty_markers.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;

namespace {

std_msgs::Header sensor_header() {
  std_msgs::Header header;
  header.frame_id = "velodyne";
  header.stamp = ros::Time(100.0);
  return header;
}

// A covariance of 1 cm everywhere but `sigma` along the unit `direction` of the translation.
Matrix6d covariance_along(const Eigen::Vector3d& direction, double sigma) {
  Matrix6d covariance = Matrix6d::Identity() * 1e-4;
  covariance.bottomRightCorner<3, 3>() +=
      (sigma * sigma - 1e-4) * direction * direction.transpose();
  return covariance;
}

Eigen::Vector3d bar_end(const visualization_msgs::Marker& bar) {
  return Eigen::Vector3d(bar.points[1].x, bar.points[1].y, bar.points[1].z);
}

}  // namespace

TEST(UncertaintyMarkers, TheBarRunsThreeSigmaAlongTheLeastKnownDirection) {
  const Eigen::Vector3d along = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  const visualization_msgs::MarkerArray markers =
      uncertainty_markers(sensor_header(), covariance_along(along, 0.2), WeakestDirection());
  ASSERT_EQ(markers.markers.size(), 2u);
  const visualization_msgs::Marker& bar = markers.markers[0];
  EXPECT_EQ(bar.header.frame_id, "velodyne");
  EXPECT_EQ(bar.action, visualization_msgs::Marker::ADD);
  ASSERT_EQ(bar.points.size(), 2u);
  EXPECT_NEAR(std::abs(bar_end(bar).dot(along)), 0.6, 1e-9);
  EXPECT_NEAR(bar_end(bar).norm(), 0.6, 1e-9);
  EXPECT_GT(bar.color.g, bar.color.r) << "green: the LiDAR fixes every direction";
  EXPECT_EQ(markers.markers[1].text, "pose 3 sigma 0.60 m");
}

TEST(UncertaintyMarkers, AnUnknownDirectionIsCappedAndSaysSo) {
  WeakestDirection blind;
  blind.degenerate = true;
  const visualization_msgs::MarkerArray markers = uncertainty_markers(
      sensor_header(), covariance_along(Eigen::Vector3d::UnitX(), 100.0), blind);
  EXPECT_NEAR(bar_end(markers.markers[0]).norm(), kMaxBarHalfLength, 1e-9);
  EXPECT_GT(markers.markers[0].color.r, 0.9f);
  EXPECT_LT(markers.markers[0].color.g, 0.2f) << "red: nothing holds it";
  EXPECT_EQ(markers.markers[1].text, "pose unknown along the bar");

  WeakestDirection held = blind;
  held.held = true;
  const visualization_msgs::Marker bar =
      uncertainty_markers(sensor_header(), covariance_along(Eigen::Vector3d::UnitX(), 0.3), held)
          .markers[0];
  EXPECT_GT(bar.color.r, 0.9f);
  EXPECT_GT(bar.color.g, 0.4f) << "orange: a motion sensor's prior holds it";
}
