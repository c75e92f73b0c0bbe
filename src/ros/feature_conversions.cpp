#include "adaptive_lego_loam/ros/feature_conversions.h"

#include <pcl_conversions/pcl_conversions.h>

#include "adaptive_lego_loam/ros/cloud_conversions.h"

namespace adaptive_lego_loam::ros_bridge {

sensor_msgs::PointCloud2 cloud_to_ros(const Cloud& cloud, const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 msg;
  pcl::toROSMsg(cloud, msg);
  msg.header = header;
  return msg;
}

CloudPtr cloud_from_ros(const sensor_msgs::PointCloud2& msg, const std::string& source) {
  // Decoded by the one reader every cloud goes through, which checks fields and sizes.
  const Scan scan = from_ros(msg, source);
  CloudPtr cloud(new Cloud);
  cloud->reserve(scan.points.size());
  for (const ScanPoint& p : scan.points) {
    CloudPoint q;
    q.x = p.x;
    q.y = p.y;
    q.z = p.z;
    q.intensity = p.intensity;
    cloud->push_back(q);
  }
  return cloud;
}

FeatureSet mapping_features_from_ros(const sensor_msgs::PointCloud2& corners,
                                     const sensor_msgs::PointCloud2& surfaces,
                                     const sensor_msgs::PointCloud2& outliers,
                                     const MappingFeatureTopics& topics) {
  FeatureSet features;
  features.less_sharp = cloud_from_ros(corners, topics.corners);
  features.less_flat = cloud_from_ros(surfaces, topics.surfaces);
  features.outliers = cloud_from_ros(outliers, topics.outliers);
  return features;
}

sensor_msgs::PointCloud2 keyframe_positions_to_ros(const std::vector<Keyframe>& keyframes,
                                                   const std_msgs::Header& header) {
  Cloud positions;
  positions.reserve(keyframes.size());
  for (const Keyframe& keyframe : keyframes) {
    const Eigen::Vector3d& t = keyframe.pose.translation();
    CloudPoint p;
    p.x = static_cast<float>(t.x());
    p.y = static_cast<float>(t.y());
    p.z = static_cast<float>(t.z());
    p.intensity = static_cast<float>(keyframe.index);
    positions.push_back(p);
  }
  return cloud_to_ros(positions, header);
}

sensor_msgs::PointCloud2 local_map_to_ros(const LocalMap& map, const std_msgs::Header& header) {
  Cloud surround = map.corners();
  surround += map.surfaces();
  // While the map is placed again after a loop, its points are still where the keyframes were
  // before the correction: shown through it, they sit where the corrected poses say.
  if (!map.to_placement().isApprox(Eigen::Isometry3d::Identity())) {
    return cloud_to_ros(*transform_cloud(surround, map.to_placement().inverse()), header);
  }
  return cloud_to_ros(surround, header);
}

}  // namespace adaptive_lego_loam::ros_bridge
