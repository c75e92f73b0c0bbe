#pragma once
// image_projection's output as messages and back: the segmented cloud, its CloudInfo and the
// outlier cloud (all that LidarOdometry needs of a scan), and the range image's points.

#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>

#include <cstddef>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "adaptive_lego_loam/ros/cloud_info_msg.h"

namespace adaptive_lego_loam::ros_bridge {

struct SegmentedCloudMessages {
  sensor_msgs::PointCloud2 cloud;  // x, y, z, intensity, ring (= range-image row), time
  CloudInfoMsg info;
  sensor_msgs::PointCloud2 outliers;  // x, y, z, intensity, ring, time
};

SegmentedCloudMessages segmented_cloud_to_ros(const SegmentedCloud& cloud,
                                              const std_msgs::Header& header);

// The topics the three messages came from, for error messages.
struct SegmentedCloudTopics {
  std::string cloud = "segmented_cloud";
  std::string info = "segmented_cloud_info";
  std::string outliers = "outlier_cloud";
};

struct ReceivedSegmentedCloud {
  SegmentedCloud cloud;   // `ground` stays empty: it is not sent
  bool has_time = false;  // the cloud has a time field (LidarOdometry's `has_time`)
  double stamp = 0.0;
};

// Throws IoError naming the topic and the field when a message lacks a field (the cloud needs
// ring) or the three disagree (see check_cloud_info).
ReceivedSegmentedCloud segmented_cloud_from_ros(const sensor_msgs::PointCloud2& cloud,
                                                const CloudInfoMsg& info,
                                                const sensor_msgs::PointCloud2& outliers,
                                                const SegmentedCloudTopics& topics = {});
// The same into `received`, whose buffers are reused from one scan to the next.
void segmented_cloud_from_ros(const sensor_msgs::PointCloud2& cloud, const CloudInfoMsg& info,
                              const sensor_msgs::PointCloud2& outliers,
                              const SegmentedCloudTopics& topics, ReceivedSegmentedCloud& received);

CloudInfoMsg cloud_info_to_ros(const CloudInfo& info, const std_msgs::Header& header);
CloudInfo cloud_info_from_ros(const CloudInfoMsg& msg);

// Throws IoError naming `source` unless the per-point arrays have one entry per point of the
// cloud (`points`) and every row's [start, end] ring indices that feature extraction walks lie
// inside it.
void check_cloud_info(const CloudInfo& info, std::size_t points, const std::string& source);

// Every point that owns a range-image cell, in row-major order, ring = its row (LeGO-LOAM's
// full_cloud_projected).
std::vector<ScanPoint> projected_points(const RangeImage& image);

}  // namespace adaptive_lego_loam::ros_bridge
