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

TEST(FeatureConversions, FeatureCloudRoundTripIsExact) {
  Cloud cloud;
  for (int i = 0; i < 10; ++i) {
    CloudPoint p;
    p.x = 0.1f * i;
    p.y = -0.3f * i;
    p.z = 1e-3f * i;
    p.intensity = static_cast<float>(i % 4);
    cloud.push_back(p);
  }
  const sensor_msgs::PointCloud2 msg = cloud_to_ros(cloud, header_at(3.0, "velodyne"));
  EXPECT_EQ(msg.header.frame_id, "velodyne");
  EXPECT_EQ(msg.width * msg.height, 10u);
  expect_same_cloud(*cloud_from_ros(msg, "t"), cloud);

  const FeatureSet features = mapping_features_from_ros(msg, msg, msg);
  expect_same_cloud(*features.less_sharp, cloud);
  expect_same_cloud(*features.less_flat, cloud);
  expect_same_cloud(*features.outliers, cloud);
  EXPECT_TRUE(features.sharp->empty());
}

TEST(FeatureConversions, MissingFieldNamesTheFeatureTopic) {
  sensor_msgs::PointCloud2 bad;
  sensor_msgs::PointCloud2Modifier modifier(bad);
  modifier.setPointCloud2Fields(2, "x", 1, sensor_msgs::PointField::FLOAT32, "z", 1,
                                sensor_msgs::PointField::FLOAT32);
  modifier.resize(3);
  const sensor_msgs::PointCloud2 good = cloud_to_ros(Cloud(), header_at(1.0));
  try {
    mapping_features_from_ros(good, bad, good, {"/c", "/laser_cloud_surf_last", "/o"});
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/laser_cloud_surf_last: missing field y"),
              std::string::npos)
        << e.what();
  }
}

TEST(FeatureConversions, KeyframePositionsAndLocalMap) {
  std::vector<Keyframe> keyframes(2);
  keyframes[1].index = 1;
  keyframes[1].pose.translation() = Eigen::Vector3d(4, -2, 0.5);
  const Cloud positions = *cloud_from_ros(keyframe_positions_to_ros(keyframes, header_at(1)), "k");
  ASSERT_EQ(positions.size(), 2u);
  EXPECT_FLOAT_EQ(positions[1].x, 4.f);
  EXPECT_FLOAT_EQ(positions[1].z, 0.5f);
  EXPECT_FLOAT_EQ(positions[1].intensity, 1.f);

  MappingParams params;
  LocalMap map(params);
  Keyframe keyframe;
  Cloud corners, surfaces;
  CloudPoint p;
  p.x = 1.f;
  corners.push_back(p);
  p.x = 2.f;
  surfaces.push_back(p);
  p.x = 3.f;
  surfaces.push_back(p);
  keyframe.corners = pack(corners);
  keyframe.surfaces = pack(surfaces);
  map.update({keyframe}, Eigen::Vector3d::Zero());
  const Cloud surround = *cloud_from_ros(local_map_to_ros(map, header_at(1, "map")), "s");
  EXPECT_EQ(surround.size(), map.corners().size() + map.surfaces().size());
  EXPECT_GE(surround.size(), 2u);

  // A loop moved the keyframes 1 m along y: until the map is placed again, what is shown is its
  // old placement moved by the correction, where the corrected keyframe says the points are.
  std::vector<Keyframe> placed(3, keyframe);  // three, so that placing them again takes two scans
  for (int i = 0; i < 3; ++i)
    placed[i].index = i;
  map.update(placed, Eigen::Vector3d::Zero());
  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  correction.translation().y() = 1.0;
  for (Keyframe& moved : placed)
    moved.pose = correction;
  map.keyframes_moved(correction);
  map.update(placed, Eigen::Vector3d::Zero());
  ASSERT_FALSE(map.to_placement().isApprox(Eigen::Isometry3d::Identity()));
  const Cloud shown = *cloud_from_ros(local_map_to_ros(map, header_at(2, "map")), "s");
  ASSERT_FALSE(shown.empty());
  for (const CloudPoint& point : shown)
    EXPECT_NEAR(point.y, 1.f, 1e-5f);
}
