// The checker of test/graph.test. Writes KITTI 07's five scans to a bag with kitti_to_bag's
// writer, then plays them in lock step (each scan once the previous one is mapped) with /clock
// through the four stages (nodes, nodelets, or two launches), a malformed and a NaN-only cloud
// between two good scans, and compares what comes out with the ground truth and with the
// offline Pipeline on the same scans; then saves the map through the save_map service. With
// ~map (test/graph/localization.test) it checks localization on that saved map instead.

#include <adaptive_lego_loam/DegenerationState.h>
#include <adaptive_lego_loam/SaveMap.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <Eigen/Eigenvalues>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include "support/run_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/io/map_files.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/kitti_bag.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "graph/graph_player.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::graph_test;
namespace fs = std::filesystem;

namespace {

constexpr int kMalformedAfterScan = 2;  // the bad clouds go between scans 2 and 3
constexpr double kReplayShift = 10.0;   // s: the replayed scans are this much older
constexpr int kEmptyFrameScan = 1;      // sent with an empty frame_id

struct Bag {
  std::vector<sensor_msgs::PointCloud2> clouds;
  std::vector<Eigen::Isometry3d> truth;  // lidar frame
};

Bag write_and_read_bag(const std::string& dir) {
  ros_bridge::KittiBagOptions options;
  options.input = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  options.output = dir + "/kitti07.bag";
  options.config_path = std::string(CONFIG_DIR) + "/kitti.yaml";
  options.start_time = 2 * kReplayShift;  // room to replay the scans earlier (stamps stay > 0)
  ros_bridge::write_kitti_bag(options);
  rosbag::Bag bag(options.output, rosbag::bagmode::Read);
  Bag contents;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    if (const auto cloud = m.instantiate<sensor_msgs::PointCloud2>()) {
      contents.clouds.push_back(*cloud);
    } else if (const auto truth = m.instantiate<nav_msgs::Odometry>()) {
      contents.truth.push_back(ros_bridge::pose_from_ros(truth->pose.pose, "ground_truth"));
    }
  }
  return contents;
}

// The config the nodes run with: ~config, else config/kitti.yaml.
std::string graph_config_path() {
  std::string path;
  ros::NodeHandle("~").getParam("config", path);
  return path.empty() ? std::string(CONFIG_DIR) + "/kitti.yaml" : path;
}

sensor_msgs::PointCloud2 cloud_without_z(const std_msgs::Header& header) {
  sensor_msgs::PointCloud2 msg;
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2Fields(3, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1,
                                sensor_msgs::PointField::FLOAT32, "intensity", 1,
                                sensor_msgs::PointField::FLOAT32);
  modifier.resize(100);
  msg.header = header;
  return msg;
}

sensor_msgs::PointCloud2 nan_cloud(const std_msgs::Header& header) {
  std::vector<ScanPoint> points(100);
  for (ScanPoint& p : points)
    p.x = p.y = p.z = std::nanf("");
  return ros_bridge::to_ros(points, header, true);
}

class Graph : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("alego_graph_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    bag_ = write_and_read_bag(dir_.string());
    config_ = load_config(graph_config_path());
    offline_ = run_offline(bag_.clouds);

    Player player(recording_);
    graph_ready_ = player.wait_for_graph();
    if (!graph_ready_) return;
    degeneration_subscribers_ = registered_nodes(1, "/degeneration");
    for (std::size_t i = 0; i < bag_.clouds.size(); ++i) {
      sensor_msgs::PointCloud2 cloud = bag_.clouds[i];
      // A driver that leaves the frame empty: the stages take ~sensor_frame (velodyne).
      if (static_cast<int>(i) == kEmptyFrameScan) cloud.header.frame_id.clear();
      recording_.every_scan_mapped &= player.play(cloud);
      if (static_cast<int>(i) != kMalformedAfterScan) continue;
      std_msgs::Header header = bag_.clouds[i].header;
      header.stamp += ros::Duration(0.03);
      player.send(cloud_without_z(header));
      saw_missing_field_warning_ = player.wait_for_warning("missing field z");
      header.stamp += ros::Duration(0.03);
      player.send(nan_cloud(header));
      saw_nan_warning_ = player.wait_for_warning("NaN");
    }
    const ros::Time last = bag_.clouds.back().header.stamp;
    recording_.tf_map_to_sensor = player.lookup("map", bag_.clouds.back().header.frame_id, last);
    saw_dropped_in_diagnostics_ =
        player.wait_for_diagnostic("image_projection: scans", "dropped: bad cloud", "2");
    save_map_ = call_save_map((dir_ / "map").string());
    if (save_map_) {
      saw_saved_keyframes_in_diagnostics_ = player.wait_for_diagnostic(
          "map_optimization: scans", "keyframes", std::to_string(save_map_->keyframes));
    }
    // A folder inside a file cannot be made: the service says so and the node goes on.
    std::ofstream(dir_ / "a_file") << "not a folder\n";
    failed_save_map_ = call_save_map((dir_ / "a_file" / "map").string());
    save_map_after_failure_ = call_save_map((dir_ / "map_again").string());
    // A bag played again: the first two scans, 10 s earlier than before.
    for (int i = 0; i < 2; ++i) {
      sensor_msgs::PointCloud2 cloud = bag_.clouds[i];
      cloud.header.stamp -= ros::Duration(kReplayShift);
      replayed_ &= player.play(cloud);
    }
    wait_for([] { return recording_.time_jump_warnings.size() >= 4; }, 5.0);
  }

  static std::optional<SaveMap::Response> call_save_map(const std::string& folder) {
    SaveMap service;
    service.request.folder = folder;
    if (!ros::service::waitForService("/map_optimization/save_map", ros::Duration(10.0)) ||
        !ros::service::call("/map_optimization/save_map", service)) {
      return std::nullopt;
    }
    return service.response;
  }

  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::vector<Eigen::Isometry3d> run_offline(
      const std::vector<sensor_msgs::PointCloud2>& clouds) {
    Pipeline pipeline(config_);
    std::vector<Eigen::Isometry3d> poses;
    for (const auto& cloud : clouds)
      poses.push_back(pipeline.process(ros_bridge::from_ros(cloud, "bag")).pose);
    return poses;
  }

  void SetUp() override { ASSERT_TRUE(graph_ready_) << "the nodes did not come up"; }

  static inline fs::path dir_;
  static inline Config config_;
  static inline std::vector<std::string> degeneration_subscribers_;
  static inline Bag bag_;
  static inline std::vector<Eigen::Isometry3d> offline_;
  static inline Recording recording_;
  static inline bool graph_ready_ = false;
  static inline bool saw_missing_field_warning_ = false;
  static inline bool saw_nan_warning_ = false;
  static inline bool saw_dropped_in_diagnostics_ = false;
  static inline bool saw_saved_keyframes_in_diagnostics_ = false;
  static inline bool replayed_ = true;
  static inline std::optional<SaveMap::Response> save_map_, failed_save_map_,
      save_map_after_failure_;
};

TEST_F(Graph, EveryScanIsMappedOnce) {
  EXPECT_TRUE(recording_.every_scan_mapped);
  ASSERT_EQ(recording_.mapped.size(), bag_.clouds.size() + 2) << "the scans and two replayed";
  for (const auto& cloud : bag_.clouds)
    EXPECT_EQ(recording_.mapped.count(cloud.header.stamp), 1u) << cloud.header.stamp;
}

TEST_F(Graph, FinalMappedPoseWithin5cmOfGroundTruth) {
  ASSERT_EQ(bag_.truth.size(), bag_.clouds.size());
  ASSERT_TRUE(recording_.mapped.count(bag_.clouds.back().header.stamp));
  const Eigen::Isometry3d& last = recording_.mapped.at(bag_.clouds.back().header.stamp);
  const double error = (last.translation() - bag_.truth.back().translation()).norm();
  EXPECT_LT(error, 0.05);
  EXPECT_GT(bag_.truth.back().translation().norm(), 0.3) << "the sensor should have moved";
}

TEST_F(Graph, SamePosesAsTheOfflinePipeline) {
  ASSERT_EQ(offline_.size(), bag_.clouds.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < bag_.clouds.size(); ++i) {
    const auto it = recording_.mapped.find(bag_.clouds[i].header.stamp);
    ASSERT_NE(it, recording_.mapped.end()) << "scan " << i;
    largest = std::max(largest, (it->second.translation() - offline_[i].translation()).norm());
    EXPECT_LT((it->second.translation() - offline_[i].translation()).norm(), 1e-6) << "scan " << i;
    EXPECT_LT(angle_between(it->second, offline_[i]), 1e-6) << "scan " << i;
  }
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", largest);
  RecordProperty("largest_translation_difference_m", text);
}

TEST_F(Graph, TimeGoingBackStartsEveryStageOverWithAWarning) {
  EXPECT_TRUE(replayed_) << "the replayed scans were not mapped";
  for (const char* stage :
       {"image_projection", "feature_association", "map_optimization", "transform_fusion"}) {
    bool warned = false;
    for (const std::string& line : recording_.time_jump_warnings)
      warned |= line.rfind(std::string(stage) + ": time went back", 0) == 0;
    EXPECT_TRUE(warned) << stage;
  }
  // As a fresh start on the same scans: the offline pipeline's poses.
  for (int i = 0; i < 2; ++i) {
    const ros::Time stamp = bag_.clouds[i].header.stamp - ros::Duration(kReplayShift);
    const auto it = recording_.mapped.find(stamp);
    ASSERT_NE(it, recording_.mapped.end()) << "replayed scan " << i;
    EXPECT_LT((it->second.translation() - offline_[i].translation()).norm(), 1e-6) << i;
  }
}

TEST_F(Graph, AScanWithAnEmptyFrameIsMappedInTheSensorFrame) {
  const ros::Time stamp = bag_.clouds[kEmptyFrameScan].header.stamp;
  ASSERT_TRUE(recording_.mapped_child_frame.count(stamp));
  EXPECT_EQ(recording_.mapped_child_frame.at(stamp), "velodyne");
  EXPECT_EQ(recording_.mapped_child_frame.at(bag_.clouds.back().header.stamp), "velodyne");
}

TEST_F(Graph, MapOptimizationPairsTheDegenerationWithEveryScan) {
  // ~mapping_node: the node that registers map_optimization's topics (a nodelet's manager).
  const std::string mapping_node =
      ros::NodeHandle("~").param<std::string>("mapping_node", "/map_optimization");
  const bool subscribed = std::count(degeneration_subscribers_.begin(),
                                     degeneration_subscribers_.end(), mapping_node) > 0;
  EXPECT_TRUE(subscribed) << "the pose's covariance weighs the scene's weak direction";
}

TEST_F(Graph, DegenerationHasValidMuForEveryScan) {
  ASSERT_EQ(recording_.degeneration.size(), bag_.clouds.size() + 2) << "and two replayed";
  for (const auto& [stamp, msg] : recording_.degeneration) {
    EXPECT_TRUE(msg.valid) << stamp;
    EXPECT_GE(msg.mu, 0.0) << stamp;
    EXPECT_LE(msg.mu, 1.0) << stamp;
    EXPECT_GE(msg.beta0_deg, 10.0f - 1e-4f) << stamp;
    EXPECT_LE(msg.beta0_deg, 60.0f + 1e-4f) << stamp;
    EXPECT_GT(msg.skeleton_points, 0u) << stamp;
  }
}

namespace {

// A published covariance: finite, symmetric, no negative variance.
void expect_covariance(const Recording::Covariance& covariance, const std::string& what) {
  EXPECT_TRUE(covariance.allFinite()) << what;
  EXPECT_LT((covariance - covariance.transpose()).cwiseAbs().maxCoeff(), 1e-9) << what;
  const Eigen::SelfAdjointEigenSolver<Recording::Covariance> solver(covariance);
  EXPECT_GE(solver.eigenvalues().minCoeff(), -1e-9) << what;
}

double position_variance(const Recording::Covariance& covariance) {
  return covariance.topLeftCorner<3, 3>().trace();
}

}  // namespace

// The three poses carry covariances: each is zero at the first scan, which defines the odometry's
// frame and the map's; then the odometry's grows scan after scan, the mapped pose's is the scan's
// place in the map, the fused one's mapping's grown by the odometry since.
TEST_F(Graph, EveryPoseCarriesItsCovariance) {
  ASSERT_EQ(recording_.odometry_covariance.size(), bag_.clouds.size() + 2) << "and two replayed";
  double last_odometry = -1.0;
  for (std::size_t i = 0; i < bag_.clouds.size(); ++i) {
    const ros::Time& stamp = bag_.clouds[i].header.stamp;
    ASSERT_TRUE(recording_.odometry_covariance.count(stamp) &&
                recording_.mapped_covariance.count(stamp) &&
                recording_.integrated_covariance.count(stamp))
        << "scan " << i;
    const std::string scan = "scan " + std::to_string(i);
    expect_covariance(recording_.odometry_covariance.at(stamp), "odometry, " + scan);
    expect_covariance(recording_.mapped_covariance.at(stamp), "mapped, " + scan);
    expect_covariance(recording_.integrated_covariance.at(stamp), "integrated, " + scan);
    const double odometry = position_variance(recording_.odometry_covariance.at(stamp));
    const double integrated = position_variance(recording_.integrated_covariance.at(stamp));
    const double mapped = position_variance(recording_.mapped_covariance.at(stamp));
    if (i == 0) {
      EXPECT_EQ(odometry, 0.0);
      EXPECT_EQ(mapped, 0.0);
      EXPECT_EQ(integrated, 0.0);
    } else {
      EXPECT_GT(odometry, last_odometry) << scan;
      EXPECT_GT(mapped, 0.0) << scan;
      EXPECT_GT(integrated, 0.0) << scan;
    }
    last_odometry = odometry;
  }
}

TEST_F(Graph, MalformedCloudsAreLoggedDroppedAndTheNextScanMapped) {
  EXPECT_TRUE(saw_missing_field_warning_);
  EXPECT_TRUE(saw_nan_warning_);
  bool names_topic = false;
  for (const std::string& line : recording_.image_projection_warnings)
    names_topic |= line.find("/velodyne_points") != std::string::npos;
  EXPECT_TRUE(names_topic);
  // No output for the bad clouds (every degeneration is a scan's); both scans after them mapped.
  for (const auto& [stamp, msg] : recording_.degeneration)
    EXPECT_EQ(recording_.mapped.count(stamp), 1u) << stamp;
  for (std::size_t i = kMalformedAfterScan + 1; i < bag_.clouds.size(); ++i)
    EXPECT_EQ(recording_.mapped.count(bag_.clouds[i].header.stamp), 1u) << "scan " << i;
}

TEST_F(Graph, DiagnosticsCountTheDroppedClouds) {
  EXPECT_TRUE(saw_dropped_in_diagnostics_);
  const auto it = recording_.diagnostics.find("image_projection: scans");
  ASSERT_NE(it, recording_.diagnostics.end()) << "no image_projection status on /diagnostics";
  std::map<std::string, std::string> values = values_of(it->second);
  EXPECT_EQ(values["scans dropped (total)"], "2");
  EXPECT_EQ(values["beta0 mode"], "adaptive");
  EXPECT_FALSE(values["mu"].empty());
  for (const char* node :
       {"feature_association: scans", "map_optimization: scans", "transform_fusion: scans"})
    EXPECT_TRUE(recording_.diagnostics.count(node)) << node;
}

TEST_F(Graph, SaveMapWritesWhatPclReadsBack) {
  ASSERT_TRUE(save_map_) << "save_map did not answer";
  ASSERT_TRUE(save_map_->success) << save_map_->message;
  const fs::path map = dir_ / "map";
  EXPECT_NE(save_map_->message.find(map.string()), std::string::npos) << save_map_->message;
  const SavedMap saved = load_map(map.string());
  EXPECT_EQ(static_cast<int>(saved.keyframes.size()), save_map_->keyframes);
  EXPECT_GE(save_map_->keyframes, 1);
  EXPECT_TRUE(saw_saved_keyframes_in_diagnostics_)
      << "map_optimization's keyframe count on /diagnostics is not the saved one";
  for (const char* file : {"global_map.pcd", "corner_map.pcd", "surface_map.pcd"}) {
    pcl::PointCloud<pcl::PointXYZI> cloud;
    ASSERT_EQ(pcl::io::loadPCDFile((map / file).string(), cloud), 0) << file;
    EXPECT_GT(cloud.size(), 1000u) << file;
  }
  pcl::PointCloud<pcl::PointXYZI> keyframe;
  EXPECT_EQ(pcl::io::loadPCDFile((map / "keyframes" / "000000_surfaces.pcd").string(), keyframe),
            0);
  EXPECT_GT(keyframe.size(), 100u);
  EXPECT_TRUE(fs::exists(map / "keyframe_poses_kitti.txt"));
  EXPECT_TRUE(fs::exists(map / "keyframe_poses_tum.txt"));
}

TEST_F(Graph, SaveMapToAFolderThatCannotBeMadeFailsAndTheNodeGoesOn) {
  ASSERT_TRUE(failed_save_map_) << "save_map did not answer";
  EXPECT_FALSE(failed_save_map_->success);
  EXPECT_NE(failed_save_map_->message.find("a_file"), std::string::npos)
      << failed_save_map_->message;
  EXPECT_FALSE(fs::exists(dir_ / "a_file" / "map"));
  ASSERT_TRUE(save_map_after_failure_) << "map_optimization stopped answering";
  EXPECT_TRUE(save_map_after_failure_->success) << save_map_after_failure_->message;
}

TEST_F(Graph, TfChainMapOdomSensorGivesTheMappedPose) {
  ASSERT_TRUE(recording_.tf_map_to_sensor) << "no map -> velodyne transform";
  const Eigen::Isometry3d& mapped = recording_.mapped.at(bag_.clouds.back().header.stamp);
  EXPECT_LT((recording_.tf_map_to_sensor->translation() - mapped.translation()).norm(), 1e-6);
  EXPECT_LT(angle_between(*recording_.tf_map_to_sensor, mapped), 1e-6);
  // transform_fusion's output for every scan, close to the mapped pose.
  ASSERT_EQ(recording_.integrated.size(), bag_.clouds.size() + 2) << "and two replayed";
  for (const auto& [stamp, pose] : recording_.integrated)
    EXPECT_LT((pose.translation() - recording_.mapped.at(stamp).translation()).norm(), 0.05);
}

// map_optimization localizing on the map run_sequence saved of the same five scans
// (test/graph/localization.test, ~map): the scans are tracked where the map has them, the
// diagnostics say so, and /initialpose starts it again from rviz's pose, in the map frame only.
class Localization : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    map_dir_ = ros::NodeHandle("~").param<std::string>("map", "");
    if (map_dir_.empty()) return;
    map_keyframes_ = static_cast<int>(load_map(map_dir_).keyframes.size());
    dir_ = fs::temp_directory_path() / ("alego_localization_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    bag_ = write_and_read_bag(dir_.string());
    Player player(recording_);
    graph_ready_ = player.wait_for_graph();
    if (!graph_ready_) return;
    for (const auto& cloud : bag_.clouds)
      every_scan_mapped_ &= player.play(cloud);
    saw_tracking_ =
        player.wait_for_diagnostic("map_optimization: scans", "localization", "tracking");
    saw_map_keyframes_ = player.wait_for_diagnostic("map_optimization: scans", "keyframes",
                                                    std::to_string(map_keyframes_));
    tracking_status_ = recording_.diagnostics["map_optimization: scans"];
    // rviz in another fixed frame: ignored, with a warning that names the frame to use.
    player.send_initial_pose(kOffPose, "odom");
    saw_wrong_frame_warning_ = player.wait_for_warning("initial pose ignored: it is in frame odom");
    // Back at the start, 1 m and 5 deg off the truth, as a user clicks it; the first scans again,
    // later in time.
    restarted_ = player.send_initial_pose(kOffPose, "map") &&
                 player.wait_for_info("new initial pose (1.00, 0.00, 0.00)");
    for (int i = 0; i < kRestartScans; ++i) {
      sensor_msgs::PointCloud2 cloud = bag_.clouds[i];
      cloud.header.stamp += ros::Duration(kRestartDelay);
      restarted_ &= player.play(cloud);
    }
    saw_tracking_after_restart_ =
        player.wait_for_diagnostic("map_optimization: scans", "localization", "tracking");
    // 500 m from anything the map holds (beyond localization.search_radius): no alignment can
    // succeed, and after localization.lost_after_scans scans it says it is lost.
    Eigen::Isometry3d far_away = Eigen::Isometry3d::Identity();
    far_away.translation().x() = 500.0;
    sent_far_away_ = player.send_initial_pose(far_away, "map") &&
                     player.wait_for_info("new initial pose (500.00, 0.00, 0.00)");
    for (int round = 0; round < 2; ++round) {
      for (const auto& scan : bag_.clouds) {
        sensor_msgs::PointCloud2 cloud = scan;
        cloud.header.stamp += ros::Duration((2 + round) * kRestartDelay);
        player.play(cloud);
      }
    }
    saw_lost_warning_ = player.wait_for_warning("map_optimization: localization lost");
    saw_lost_in_diagnostics_ =
        player.wait_for_diagnostic("map_optimization: scans", "localization", "lost");
  }

  static void TearDownTestSuite() {
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  void SetUp() override {
    ASSERT_FALSE(map_dir_.empty()) << "no ~map: run this suite through localization.test";
    ASSERT_TRUE(graph_ready_) << "the nodes did not come up";
  }

  static constexpr int kRestartScans = 3;
  static constexpr double kRestartDelay = 10.0;  // s
  static inline const Eigen::Isometry3d kOffPose = [] {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(1.0, 0.0, 0.0));
    pose.rotate(Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
    return pose;
  }();
  static inline std::string map_dir_;
  static inline int map_keyframes_ = 0;
  static inline fs::path dir_;
  static inline Bag bag_;
  static inline Recording recording_;
  static inline bool graph_ready_ = false;
  static inline bool every_scan_mapped_ = true;
  static inline bool saw_tracking_ = false;
  static inline bool saw_map_keyframes_ = false;
  static inline bool saw_wrong_frame_warning_ = false;
  static inline bool restarted_ = false;
  static inline bool saw_tracking_after_restart_ = false;
  static inline diagnostic_msgs::DiagnosticStatus tracking_status_;  // before the restarts
  static inline bool sent_far_away_ = false;
  static inline bool saw_lost_warning_ = false;
  static inline bool saw_lost_in_diagnostics_ = false;
};

TEST_F(Localization, EveryScanIsTrackedWhereTheMapHasIt) {
  EXPECT_TRUE(every_scan_mapped_);
  for (std::size_t i = 0; i < bag_.clouds.size(); ++i) {
    const auto it = recording_.mapped.find(bag_.clouds[i].header.stamp);
    ASSERT_NE(it, recording_.mapped.end()) << "scan " << i;
    EXPECT_LT((it->second.translation() - bag_.truth[i].translation()).norm(), 0.05) << i;
    EXPECT_LT(angle_between(it->second, bag_.truth[i]), 0.01) << i;
  }
}

TEST_F(Localization, DiagnosticsSayTrackingAndCountTheSavedMapsKeyframes) {
  EXPECT_TRUE(saw_tracking_);
  EXPECT_TRUE(saw_map_keyframes_) << "keyframes on /diagnostics is not the map's "
                                  << map_keyframes_;
  std::map<std::string, std::string> values = values_of(tracking_status_);
  EXPECT_EQ(values["map"], map_dir_);
  EXPECT_FALSE(values["keyframes of this drive"].empty());
  EXPECT_EQ(values["scans lost (total)"], "0");
  EXPECT_EQ(values.count("loops closed"), 0u) << "no loop closes in localization";
}

TEST_F(Localization, AnInitialPoseInAnotherFrameIsIgnoredWithAWarning) {
  EXPECT_TRUE(saw_wrong_frame_warning_);
}

TEST_F(Localization, AnInitialPoseInTheMapFrameStartsItAgain) {
  EXPECT_TRUE(restarted_) << "the scans after the new initial pose were not all mapped";
  EXPECT_TRUE(saw_tracking_after_restart_);
  for (int i = 0; i < kRestartScans; ++i) {
    const ros::Time stamp = bag_.clouds[i].header.stamp + ros::Duration(kRestartDelay);
    const auto it = recording_.mapped.find(stamp);
    ASSERT_NE(it, recording_.mapped.end()) << "scan " << i << " after the restart";
    // Aligned from 1 m off back onto the map: where the truth is, not where the pose was put.
    EXPECT_LT((it->second.translation() - bag_.truth[i].translation()).norm(), 0.05) << i;
  }
}

TEST_F(Localization, FarFromTheMapItSaysItIsLostInTheLogAndOnDiagnostics) {
  ASSERT_TRUE(sent_far_away_) << "map_optimization did not take the far initial pose";
  EXPECT_TRUE(saw_lost_warning_);
  EXPECT_TRUE(saw_lost_in_diagnostics_);
  const diagnostic_msgs::DiagnosticStatus& status =
      recording_.diagnostics["map_optimization: scans"];
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::ERROR);
  EXPECT_NE(status.message.find("localization lost"), std::string::npos) << status.message;
  const std::string lost = values_of(status)["scans lost (total)"];
  EXPECT_FALSE(lost.empty());
  EXPECT_NE(lost, "0");
}

// Runs a node with extra arguments (at most 20 s) and returns its exit status and output.
std::pair<int, std::string> run_node_binary(const std::string& node, const std::string& arguments) {
  return adaptive_lego_loam::test::run_command("timeout 20 " + std::string(BIN_DIR) + "/" + node +
                                               " " + arguments);
}

TEST(NodeStartUp, BadConfigStopsTheNodeWithTheLoadersMessage) {
  const fs::path bad =
      fs::temp_directory_path() / ("alego_bad_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(bad) << "sensor:\n  rows: -3\n";
  const auto [status, output] =
      run_node_binary("image_projection", "__name:=bad_config_node _config:=" + bad.string());
  fs::remove(bad);
  EXPECT_EQ(status, 1) << output;
  // The loader's own words: the file, the key, the value and the allowed range.
  EXPECT_NE(output.find("sensor.rows"), std::string::npos) << output;
  EXPECT_NE(output.find("-3 is out of range: expected an integer in [1, 512]"), std::string::npos)
      << output;
  EXPECT_NE(output.find(bad.string()), std::string::npos) << output;
}

TEST(NodeStartUp, UnknownSensorNameListsTheKnownOnes) {
  const auto [status, output] =
      run_node_binary("map_optimization", "__name:=bad_sensor_node _sensor:=velodyne128");
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("velodyne128"), std::string::npos) << output;
  EXPECT_NE(output.find("(known sensors: hdl32, hdl64e, kitti, kitti_16rings, os0_64, os1_128, "
                        "os1_64, os2_128, pandar_qt64, pandar_xt32, rs_helios_32, vlp16)"),
            std::string::npos)
      << output;
}

// graph_manager (nodes.launch nodelets:=true) fails as the node does, with the loader's words.
TEST(GraphManagerStartUp, BadConfigStopsTheManagerWithTheLoadersMessage) {
  const fs::path bad =
      fs::temp_directory_path() / ("alego_bad_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(bad) << "sensor:\n  rows: -3\n";
  // The stage is loaded as <manager's namespace>/image_projection and reads its parameters there.
  ros::param::set("/bad_graph/image_projection/config", bad.string());
  const auto [status, output] = run_node_binary(
      "graph_manager", "__ns:=/bad_graph __name:=bad_manager _stages:=image_projection");
  fs::remove(bad);
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("-3 is out of range: expected an integer in [1, 512]"), std::string::npos)
      << output;
  EXPECT_NE(output.find("could not load image_projection"), std::string::npos) << output;
}

TEST(GraphManagerStartUp, UnknownStageListsTheKnownOnes) {
  const auto [status, output] = run_node_binary(
      "graph_manager", "__name:=bad_stages_manager \"_stages:=image_projection mapping\"");
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("unknown stage 'mapping'"), std::string::npos) << output;
  EXPECT_NE(output.find("image_projection, feature_association, map_optimization or "
                        "transform_fusion"),
            std::string::npos)
      << output;
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "graph_checker");
  ros::NodeHandle nh;  // keeps the node up for the whole run
  return RUN_ALL_TESTS();
}
