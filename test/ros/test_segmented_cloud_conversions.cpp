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

TEST(SegmentedCloudConversions, RealScanSurvivesTheRoundTripExactly) {
  AmbientFilter filter(kitti_config());
  const AmbientFilterResult filtered = filter_frame(filter, 0);
  const SegmentedCloud& sent = filtered.segmentation.cloud;
  ASSERT_GT(sent.points.size(), 1000u);

  const SegmentedCloudMessages messages = segmented_cloud_to_ros(sent, header_at(1.0));
  EXPECT_EQ(messages.info.header.stamp, messages.cloud.header.stamp);
  const ReceivedSegmentedCloud received =
      segmented_cloud_from_ros(messages.cloud, messages.info, messages.outliers);
  EXPECT_TRUE(received.has_time);
  EXPECT_DOUBLE_EQ(received.stamp, 1.0);
  expect_same_points(received.cloud.points, sent.points);
  expect_same_points(received.cloud.outliers, sent.outliers);
  EXPECT_EQ(received.cloud.row, sent.row);
  for (std::size_t i = 0; i < sent.points.size(); ++i)
    ASSERT_EQ(received.cloud.points[i].time, sent.points[i].time);
  const CloudInfo& info = received.cloud.info;
  EXPECT_EQ(info.start_ring_index, sent.info.start_ring_index);
  EXPECT_EQ(info.end_ring_index, sent.info.end_ring_index);
  EXPECT_EQ(info.start_orientation, sent.info.start_orientation);
  EXPECT_EQ(info.end_orientation, sent.info.end_orientation);
  EXPECT_EQ(info.orientation_diff, sent.info.orientation_diff);
  EXPECT_EQ(info.ground_flag, sent.info.ground_flag);
  EXPECT_EQ(info.column, sent.info.column);
  EXPECT_EQ(info.range, sent.info.range);
}

// feature_association receives every scan into the buffers of the one before.
TEST(SegmentedCloudConversions, AScanReceivedIntoTheBuffersOfAnotherEqualsItReceivedAlone) {
  AmbientFilter filter(kitti_config());
  const SegmentedCloudMessages first =
      segmented_cloud_to_ros(filter_frame(filter, 1).segmentation.cloud, header_at(1.0));
  const SegmentedCloudMessages second =
      segmented_cloud_to_ros(filter_frame(filter, 0).segmentation.cloud, header_at(2.0));
  ASSERT_NE(first.cloud.width, second.cloud.width);

  ReceivedSegmentedCloud reused;
  segmented_cloud_from_ros(first.cloud, first.info, first.outliers, {}, reused);
  segmented_cloud_from_ros(second.cloud, second.info, second.outliers, {}, reused);
  const ReceivedSegmentedCloud alone =
      segmented_cloud_from_ros(second.cloud, second.info, second.outliers);
  EXPECT_DOUBLE_EQ(reused.stamp, 2.0);
  expect_same_points(reused.cloud.points, alone.cloud.points);
  expect_same_points(reused.cloud.outliers, alone.cloud.outliers);
  EXPECT_EQ(reused.cloud.row, alone.cloud.row);
  EXPECT_EQ(reused.cloud.info.start_ring_index, alone.cloud.info.start_ring_index);
  EXPECT_EQ(reused.cloud.info.ground_flag, alone.cloud.info.ground_flag);
  EXPECT_EQ(reused.cloud.info.column, alone.cloud.info.column);
  EXPECT_EQ(reused.cloud.info.range, alone.cloud.info.range);
}

TEST(SegmentedCloudConversions, OdometryOnReceivedCloudsEqualsOdometryOnTheOriginals) {
  // feature_association must give what the offline Pipeline gives: two scans through
  // LidarOdometry directly and through the messages.
  Config config = kitti_config();
  config.sensor.deskewed = false;  // de-skew the second scan: the time field must not change it
  AmbientFilter filter(config);
  LidarOdometry direct(config.sensor, config.features, config.odometry);
  LidarOdometry through_messages(config.sensor, config.features, config.odometry);
  OdometryOutput direct_out, messages_out;
  for (int frame = 0; frame < 2; ++frame) {
    const AmbientFilterResult filtered = filter_frame(filter, frame);
    direct.process(filtered.segmentation.cloud, false, direct_out);
    const auto messages = segmented_cloud_to_ros(filtered.segmentation.cloud, header_at(frame));
    const auto received =
        segmented_cloud_from_ros(messages.cloud, messages.info, messages.outliers);
    through_messages.process(received.cloud, received.has_time, messages_out);
  }
  EXPECT_TRUE(direct_out.pose.matrix() == messages_out.pose.matrix());
  EXPECT_GT(direct_out.pose.translation().norm(), 0.05);
  expect_same_cloud(*direct_out.features.less_sharp, *messages_out.features.less_sharp);
  expect_same_cloud(*direct_out.features.less_flat, *messages_out.features.less_flat);
}

namespace {

// A three-point segmented cloud in one row, every index walked by feature extraction valid.
SegmentedCloud small_segmented_cloud() {
  SegmentedCloud cloud;
  cloud.points = {{1, 2, 3, 4, 0.01f}, {2, 2, 3, 4, 0.02f}, {3, 2, 3, 4, 0.03f}};
  cloud.row = {5, 5, 5};
  cloud.info.start_ring_index = {0};
  cloud.info.end_ring_index = {2};
  cloud.info.ground_flag = {0, 1, 0};
  cloud.info.column = {7, 8, 9};
  cloud.info.range = {3.7f, 4.1f, 4.7f};
  cloud.outliers = {{9, 9, 9, 1}};
  return cloud;
}

std::string receive_error(const SegmentedCloudMessages& messages) {
  try {
    segmented_cloud_from_ros(messages.cloud, messages.info, messages.outliers,
                             {"/segmented_cloud", "/segmented_cloud_info", "/outlier_cloud"});
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

// feature_association de-skews the outliers by their times as the segmented points: without
// them a raw sweep's outliers land elsewhere than offline.
TEST(SegmentedCloudConversions, OutliersKeepTheirTimes) {
  SegmentedCloud cloud = small_segmented_cloud();
  cloud.outliers = {{9, 9, 9, 1, 0.05f}, {8, 9, 9, 1, 0.07f}};
  const SegmentedCloudMessages messages = segmented_cloud_to_ros(cloud, header_at(1.0));
  const ReceivedSegmentedCloud received =
      segmented_cloud_from_ros(messages.cloud, messages.info, messages.outliers);
  ASSERT_EQ(received.cloud.outliers.size(), 2u);
  EXPECT_EQ(received.cloud.outliers[0].time, 0.05f);
  EXPECT_EQ(received.cloud.outliers[1].time, 0.07f);
}

TEST(SegmentedCloudConversions, SmallCloudKeepsRowsInTheRingField) {
  const auto messages = segmented_cloud_to_ros(small_segmented_cloud(), header_at(2.0));
  const Scan scan = from_ros(messages.cloud, "test");
  ASSERT_TRUE(scan.has_ring);
  EXPECT_EQ(scan.points[1].ring, 5);
  EXPECT_EQ(receive_error(messages), "no error");
}

TEST(SegmentedCloudConversions, CloudWithoutRingIsRejectedNamingTopicAndField) {
  const SegmentedCloud cloud = small_segmented_cloud();
  auto messages = segmented_cloud_to_ros(cloud, header_at(1.0));
  messages.cloud = to_ros(cloud.points, messages.cloud.header, false);
  EXPECT_EQ(receive_error(messages),
            "/segmented_cloud: missing field ring (the range-image row "
            "of each point)");
}

TEST(SegmentedCloudConversions, InfoOfAnotherLengthIsRejectedNamingTheField) {
  auto messages = segmented_cloud_to_ros(small_segmented_cloud(), header_at(1.0));
  messages.info.segmentedCloudRange.pop_back();
  EXPECT_EQ(receive_error(messages),
            "/segmented_cloud_info: segmentedCloudRange has 2 entries, expected one per point "
            "of the segmented cloud (3)");
}

TEST(SegmentedCloudConversions, RingIndicesOutsideTheCloudAreRejected) {
  auto messages = segmented_cloud_to_ros(small_segmented_cloud(), header_at(1.0));
  messages.info.endRingIndex[0] = 3;
  EXPECT_NE(receive_error(messages).find("/segmented_cloud_info: row 0 spans points [0, 3]"),
            std::string::npos);
  messages.info.endRingIndex = {2, 2};
  EXPECT_NE(receive_error(messages).find("startRingIndex has 1 rows, endRingIndex 2"),
            std::string::npos);
  // An empty row (start past end, as the core writes it) is fine.
  messages.info.startRingIndex = {0, 9};
  messages.info.endRingIndex = {2, -4};
  EXPECT_EQ(receive_error(messages), "no error");
}

TEST(SegmentedCloudConversions, OutlierCloudWithoutZIsRejectedNamingItsTopic) {
  auto messages = segmented_cloud_to_ros(small_segmented_cloud(), header_at(1.0));
  sensor_msgs::PointCloud2Modifier modifier(messages.outliers);
  modifier.setPointCloud2Fields(2, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1,
                                sensor_msgs::PointField::FLOAT32);
  modifier.resize(1);
  EXPECT_NE(receive_error(messages).find("/outlier_cloud: missing field z"), std::string::npos);
}

TEST(SegmentedCloudConversions, ProjectedPointsCarryTheirRow) {
  AmbientFilter filter(kitti_config());
  const AmbientFilterResult filtered = filter_frame(filter, 0);
  const RangeImage& image = filtered.segmentation.image;
  const std::vector<ScanPoint> points = projected_points(image);
  ASSERT_EQ(static_cast<int>(points.size()), image.stats().projected);
  int checked = 0;
  for (int cell = 0; cell < image.size() && checked < 50; ++cell) {
    if (!image.occupied(cell)) continue;
    EXPECT_EQ(points[checked].ring, image.row_of(cell));
    EXPECT_EQ(points[checked].x, image.point(cell).x);
    ++checked;
  }
}
