#pragma once
// The PCL clouds of the odometry and mapping stages as PointCloud2 and back: feature clouds
// (intensity = range-image row), the keyframe positions and the local map.

#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"
#include "adaptive_lego_loam/core/mapping/local_map.h"
#include "adaptive_lego_loam/core/odometry/feature_extraction.h"

namespace adaptive_lego_loam::ros_bridge {

sensor_msgs::PointCloud2 cloud_to_ros(const Cloud& cloud, const std_msgs::Header& header);

// Any PointCloud2 with x, y, z (intensity when present). Throws IoError naming `source` when a
// field is missing or the message is malformed.
CloudPtr cloud_from_ros(const sensor_msgs::PointCloud2& msg, const std::string& source);

// What LidarMapping reads of a scan's features: corners (less sharp), surfaces (less flat) and
// outliers; `sharp` and `flat` stay empty.
struct MappingFeatureTopics {
  std::string corners = "laser_cloud_corner_last";
  std::string surfaces = "laser_cloud_surf_last";
  std::string outliers = "outlier_cloud_last";
};
FeatureSet mapping_features_from_ros(const sensor_msgs::PointCloud2& corners,
                                     const sensor_msgs::PointCloud2& surfaces,
                                     const sensor_msgs::PointCloud2& outliers,
                                     const MappingFeatureTopics& topics = {});

// One point per keyframe at its position, intensity = keyframe index (LeGO-LOAM's
// key_pose_origin).
sensor_msgs::PointCloud2 keyframe_positions_to_ros(const std::vector<Keyframe>& keyframes,
                                                   const std_msgs::Header& header);

// The local map's corners and surfaces in one cloud (LeGO-LOAM's laser_cloud_surround).
sensor_msgs::PointCloud2 local_map_to_ros(const LocalMap& map, const std_msgs::Header& header);

}  // namespace adaptive_lego_loam::ros_bridge
