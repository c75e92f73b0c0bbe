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

TEST(DegenerationConversions, MessageCarriesTheFilterResult) {
  AmbientFilter filter(kitti_config());
  const AmbientFilterResult filtered = filter_frame(filter, 0);
  ASSERT_TRUE(filtered.degeneration.valid);
  const DegenerationState msg = degeneration_to_ros(filtered, header_at(1.0));
  EXPECT_TRUE(msg.valid);
  EXPECT_EQ(msg.mu, filtered.mu);
  EXPECT_EQ(msg.mu_raw, filtered.degeneration.mu);
  EXPECT_FLOAT_EQ(msg.beta0_deg, static_cast<float>(filtered.beta0_deg));
  EXPECT_EQ(msg.weak_direction.x, filtered.degeneration.weak_direction.x());
  EXPECT_EQ(msg.weak_direction.y, filtered.degeneration.weak_direction.y());
  EXPECT_EQ(msg.weak_direction.z, 0.0);
  EXPECT_EQ(static_cast<int>(msg.skeleton_points), filtered.skeleton_points);
  EXPECT_EQ(static_cast<int>(msg.normals), filtered.degeneration.normals);
}

TEST(DegenerationConversions, PriorFromTheMessageEqualsThePipelines) {
  AmbientFilter filter(kitti_config());
  const AmbientFilterResult filtered = filter_frame(filter, 0);
  const DegenerationState msg = degeneration_to_ros(filtered, header_at(1.0));
  MappingParams params;
  EXPECT_FALSE(weak_direction_prior_from_ros(params, msg)) << "off by default";
  params.weak_direction_prior = 3.0;
  const auto expected = weak_direction_prior(params, filtered);
  const auto prior = weak_direction_prior_from_ros(params, msg);
  ASSERT_TRUE(expected);
  ASSERT_TRUE(prior);
  EXPECT_EQ(prior->weight, expected->weight);
  EXPECT_TRUE(prior->direction == expected->direction);
  DegenerationState unknown = msg;
  unknown.valid = false;
  EXPECT_FALSE(weak_direction_prior_from_ros(params, unknown));
}

TEST(DegenerationConversions, MarkersShowTheWeakDirectionAndMu) {
  DegenerationState msg;
  msg.header = header_at(1.0, "velodyne");
  msg.valid = true;
  msg.mu = 0.5;
  msg.beta0_deg = 35.f;
  msg.weak_direction.x = 0.6;
  msg.weak_direction.y = 0.8;
  const auto markers = degeneration_markers(msg);
  ASSERT_EQ(markers.markers.size(), 2u);
  const auto& arrow = markers.markers[0];
  EXPECT_EQ(arrow.type, visualization_msgs::Marker::ARROW);
  EXPECT_EQ(arrow.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(arrow.header.frame_id, "velodyne");
  ASSERT_EQ(arrow.points.size(), 2u);
  EXPECT_NEAR(arrow.points[1].x, 0.6 * 7.0, 1e-12);  // 2 m + 10 m * mu
  EXPECT_NEAR(arrow.points[1].y, 0.8 * 7.0, 1e-12);
  EXPECT_EQ(markers.markers[1].text, "mu 0.50  beta0 35.0 deg");

  msg.valid = false;
  const auto unknown = degeneration_markers(msg);
  EXPECT_EQ(unknown.markers[0].action, visualization_msgs::Marker::DELETE);
  EXPECT_EQ(unknown.markers[1].text, "mu unknown  beta0 35.0 deg");
}
