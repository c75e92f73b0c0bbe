// Conversions of the nodes' messages: what image_projection sends feature_association, the
// feature clouds, poses, odometry and TF, and the degeneration state.

#include <gtest/gtest.h>

#include <sensor_msgs/point_cloud2_iterator.h>

#include <cmath>

#include "adaptive_lego_loam/core/ambient_filter.h"
#include "adaptive_lego_loam/core/lidar_odometry.h"
#include "adaptive_lego_loam/core/pipeline.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/degeneration_conversions.h"
#include "adaptive_lego_loam/ros/feature_conversions.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/ros/segmented_cloud_conversions.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;

namespace {

const std::string kScans = std::string(TEST_DATA_DIR) + "/kitti_seq07/velodyne/";

Config kitti_config() {
  return load_config(std::string(CONFIG_DIR) + "/kitti.yaml");
}

// The ambient filter's result on KITTI 07 frame `index`.
AmbientFilterResult filter_frame(AmbientFilter& filter, int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "%010d.bin", index);
  AmbientFilterResult result;
  filter.process(read_kitti_bin(kScans + name), result);
  return result;
}

std_msgs::Header header_at(double seconds, const std::string& frame = "velodyne") {
  std_msgs::Header header;
  header.stamp.fromSec(seconds);
  header.frame_id = frame;
  return header;
}

void expect_same_points(const std::vector<ScanPoint>& a, const std::vector<ScanPoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].z, b[i].z) << i;
    ASSERT_EQ(a[i].intensity, b[i].intensity) << i;
  }
}

void expect_same_cloud(const Cloud& a, const Cloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].z, b[i].z) << i;
    ASSERT_EQ(a[i].intensity, b[i].intensity) << i;
  }
}

}  // namespace

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
  keyframe.corners.reset(new Cloud);
  keyframe.surfaces.reset(new Cloud);
  keyframe.outliers.reset(new Cloud);
  CloudPoint p;
  p.x = 1.f;
  keyframe.corners->push_back(p);
  p.x = 2.f;
  keyframe.surfaces->push_back(p);
  p.x = 3.f;
  keyframe.surfaces->push_back(p);
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
