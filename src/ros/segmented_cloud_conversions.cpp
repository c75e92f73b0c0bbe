#include "adaptive_lego_loam/ros/segmented_cloud_conversions.h"

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

void check_length(std::size_t entries, std::size_t points, const std::string& source,
                  const std::string& field) {
  if (entries == points) return;
  throw IoError(source + ": " + field + " has " + std::to_string(entries) +
                " entries, expected one per point of the segmented cloud (" +
                std::to_string(points) + ")");
}

// Copies into `info`'s existing buffers.
void assign_cloud_info(const CloudInfoMsg& msg, CloudInfo& info) {
  info.start_ring_index = msg.startRingIndex;
  info.end_ring_index = msg.endRingIndex;
  info.start_orientation = msg.startOrientation;
  info.end_orientation = msg.endOrientation;
  info.orientation_diff = msg.orientationDiff;
  info.ground_flag.assign(msg.segmentedCloudGroundFlag.begin(), msg.segmentedCloudGroundFlag.end());
  info.column = msg.segmentedCloudColInd;
  info.range = msg.segmentedCloudRange;
}

}  // namespace

CloudInfoMsg cloud_info_to_ros(const CloudInfo& info, const std_msgs::Header& header) {
  CloudInfoMsg msg;
  msg.header = header;
  msg.startRingIndex = info.start_ring_index;
  msg.endRingIndex = info.end_ring_index;
  msg.startOrientation = info.start_orientation;
  msg.endOrientation = info.end_orientation;
  msg.orientationDiff = info.orientation_diff;
  msg.segmentedCloudGroundFlag = info.ground_flag;
  msg.segmentedCloudColInd = info.column;
  msg.segmentedCloudRange = info.range;
  return msg;
}

CloudInfo cloud_info_from_ros(const CloudInfoMsg& msg) {
  CloudInfo info;
  assign_cloud_info(msg, info);
  return info;
}

void check_cloud_info(const CloudInfo& info, std::size_t points, const std::string& source) {
  check_length(info.ground_flag.size(), points, source, "segmentedCloudGroundFlag");
  check_length(info.column.size(), points, source, "segmentedCloudColInd");
  check_length(info.range.size(), points, source, "segmentedCloudRange");
  if (info.start_ring_index.size() != info.end_ring_index.size()) {
    throw IoError(source + ": startRingIndex has " + std::to_string(info.start_ring_index.size()) +
                  " rows, endRingIndex " + std::to_string(info.end_ring_index.size()));
  }
  const long long size = static_cast<long long>(points);
  for (std::size_t row = 0; row < info.start_ring_index.size(); ++row) {
    const int32_t start = info.start_ring_index[row], end = info.end_ring_index[row];
    if (start > end) continue;  // an empty or short row: nothing is read
    if (start < 0 || end >= size) {
      throw IoError(source + ": row " + std::to_string(row) + " spans points [" +
                    std::to_string(start) + ", " + std::to_string(end) +
                    "], outside the segmented cloud's " + std::to_string(points));
    }
  }
}

SegmentedCloudMessages segmented_cloud_to_ros(const SegmentedCloud& cloud,
                                              const std_msgs::Header& header) {
  SegmentedCloudMessages messages;
  messages.cloud = to_ros(cloud.points, cloud.row, header);
  messages.info = cloud_info_to_ros(cloud.info, header);
  // With their times: feature_association de-skews them as the segmented points.
  messages.outliers = to_ros(cloud.outliers, header, true);
  return messages;
}

ReceivedSegmentedCloud segmented_cloud_from_ros(const sensor_msgs::PointCloud2& cloud,
                                                const CloudInfoMsg& info,
                                                const sensor_msgs::PointCloud2& outliers,
                                                const SegmentedCloudTopics& topics) {
  ReceivedSegmentedCloud received;
  segmented_cloud_from_ros(cloud, info, outliers, topics, received);
  return received;
}

void segmented_cloud_from_ros(const sensor_msgs::PointCloud2& cloud, const CloudInfoMsg& info,
                              const sensor_msgs::PointCloud2& outliers,
                              const SegmentedCloudTopics& topics,
                              ReceivedSegmentedCloud& received) {
  SegmentedCloud& segmented = received.cloud;
  Scan scan;
  scan.points.swap(segmented.points);  // decoded into the previous message's buffer
  from_ros(cloud, topics.cloud, scan);
  if (!scan.has_ring) {
    throw IoError(topics.cloud + ": missing field ring (the range-image row of each point)");
  }
  received.has_time = scan.has_time;
  received.stamp = scan.stamp;
  segmented.row.resize(scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i)
    segmented.row[i] = static_cast<uint16_t>(scan.points[i].ring);
  segmented.points.swap(scan.points);
  assign_cloud_info(info, segmented.info);
  check_cloud_info(segmented.info, segmented.points.size(), topics.info);
  scan.points.swap(segmented.outliers);
  from_ros(outliers, topics.outliers, scan);
  segmented.outliers.swap(scan.points);
}

std::vector<ScanPoint> projected_points(const RangeImage& image) {
  std::vector<ScanPoint> points;
  points.reserve(image.stats().projected);
  for (int cell = 0; cell < image.size(); ++cell) {
    if (!image.occupied(cell)) continue;
    ScanPoint p = image.point(cell);
    p.ring = image.row_of(cell);
    points.push_back(p);
  }
  return points;
}

}  // namespace adaptive_lego_loam::ros_bridge
