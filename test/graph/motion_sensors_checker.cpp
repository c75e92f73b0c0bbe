// The checker of test/graph/motion_sensors.test. Plays a simulated drive's bag (/velodyne_points,
// /imu/data, /odom, /tf_static) through the graph in lock step: each scan after the samples up to
// its stamp, then the samples up to the next scan's, and the next scan once this one is mapped.
// Compares the mapped poses with run_sequence's on the same bag (~reference, its output folder) and
// /diagnostics with its summary.json. The Drive suite plays the fault-free drive; the Faults suite
// (drive:=faults) the same drive with faulty samples, and also compares with the fault-free run
// (~clean_reference). drive:=tunnel plays a bare tunnel with the follow test on in the Drive suite.

#include <diagnostic_msgs/DiagnosticStatus.h>
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2/buffer_core.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/ros/motion_sensor_relay.h"
#include "graph/graph_player.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::graph_test;

namespace {

constexpr char kFeatureAssociation[] = "feature_association: scans";

// Each topic's messages in the bag's order (as run_sequence reads them).
struct SimulatedDrive {
  std::vector<sensor_msgs::PointCloud2> clouds;
  std::vector<sensor_msgs::Imu> imu;
  std::vector<nav_msgs::Odometry> odometry;
  tf2_msgs::TFMessage static_transforms;
};

template <class Message>
std::vector<Message> read_topic(const rosbag::Bag& bag, const std::string& topic) {
  std::vector<Message> messages;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topic)))
    messages.push_back(*m.instantiate<Message>());
  return messages;
}

SimulatedDrive read_drive(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  SimulatedDrive drive;
  drive.clouds = read_topic<sensor_msgs::PointCloud2>(bag, "/velodyne_points");
  drive.imu = read_topic<sensor_msgs::Imu>(bag, "/imu/data");
  drive.odometry = read_topic<nav_msgs::Odometry>(bag, "/odom");
  const auto transforms = read_topic<tf2_msgs::TFMessage>(bag, "/tf_static");
  if (!transforms.empty()) drive.static_transforms = transforms.front();
  return drive;
}

// Sends each input's messages in their order up to the first one stamped after `bound` (s), as
// run_sequence hands samples over up to a scan's stamp.
template <class Message, class Send>
void send_until(const std::vector<Message>& messages, std::size_t& next, double bound, Send send) {
  for (; next < messages.size() && messages[next].header.stamp.toSec() <= bound; ++next)
    send(messages[next]);
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

std::string param(const std::string& name) {
  return ros::NodeHandle("~").param<std::string>(name, "");
}

// A /diagnostics value of feature_association's status.
std::string sensor_value(const Recording& recording, const std::string& key) {
  const auto it = recording.diagnostics.find(kFeatureAssociation);
  if (it == recording.diagnostics.end()) return "(no status)";
  const auto values = values_of(it->second);
  const auto entry = values.find(key);
  return entry == values.end() ? "(no " + key + ")" : entry->second;
}

// What both suites do: the drive played through the graph.
struct PlayedDrive {
  SimulatedDrive drive;
  std::vector<Eigen::Isometry3d> reference;  // run_sequence's poses on the same bag
  nlohmann::json summary;                    // ... and its summary.json
  Recording recording;
  bool graph_ready = false;
  bool every_scan_mapped = true;
  bool saw_final_counts = false;
  std::vector<std::string> priors_subscribers;

  void play() {
    drive = read_drive(param("bag"));
    reference = read_kitti_poses(param("reference") + "/poses_kitti.txt");
    summary = read_json(param("reference") + "/summary.json");
    Player player(recording);
    player.advertise_motion_sensors("/imu/data", "/odom");
    player.record_gravity_markers();
    player.send_static_transforms(drive.static_transforms);
    graph_ready = player.wait_for_graph(
        {"/imu/data", "/odom", "/motion_priors", "/map_match", "/gravity_marker"});
    if (!graph_ready) return;
    priors_subscribers = registered_nodes(1, "/motion_priors");
    // Each scan with the samples up to its stamp, then those up to the next scan's (a sample at
    // or after its stamp lets feature_association go on), then the next once it is mapped.
    std::size_t next_imu = 0, next_odometry = 0;
    const auto send_samples = [&](double bound) {
      send_until(drive.imu, next_imu, bound, [&](const auto& m) { player.send_imu(m); });
      send_until(drive.odometry, next_odometry, bound,
                 [&](const auto& m) { player.send_odometry(m); });
    };
    for (std::size_t i = 0; i < drive.clouds.size(); ++i) {
      const ros::Time stamp = drive.clouds[i].header.stamp;
      send_samples(stamp.toSec());
      player.send(drive.clouds[i]);
      if (i + 1 < drive.clouds.size()) send_samples(drive.clouds[i + 1].header.stamp.toSec());
      every_scan_mapped &= player.wait_until_mapped(stamp);
    }
    // The counts of the last scan, as summary.json has them after the run.
    saw_final_counts = player.wait_for_diagnostic(
        kFeatureAssociation, "IMU scans used",
        std::to_string(summary["motion_sensors"]["imu"]["scans_used"].get<long>()));
  }

  // The mapped pose of each scan against `poses` (one a scan): the largest translation and
  // rotation differences from scan `from` on.
  std::pair<double, double> largest_difference(const std::vector<Eigen::Isometry3d>& poses,
                                               std::size_t from = 0) const {
    double translation = 0.0, rotation = 0.0;
    for (std::size_t i = from; i < drive.clouds.size() && i < poses.size(); ++i) {
      const auto it = recording.mapped.find(drive.clouds[i].header.stamp);
      if (it == recording.mapped.end()) return {INFINITY, INFINITY};
      translation =
          std::max(translation, (it->second.translation() - poses[i].translation()).norm());
      rotation = std::max(rotation, angle_between(it->second, poses[i]));
    }
    return {translation, rotation};
  }

  void expect_every_scan_mapped() const {
    EXPECT_TRUE(every_scan_mapped);
    EXPECT_EQ(recording.mapped.size(), drive.clouds.size());
    EXPECT_EQ(drive.clouds.size(), reference.size());
  }

  void expect_run_sequences_poses() const {
    ASSERT_EQ(reference.size(), drive.clouds.size());
    const auto [translation, rotation] = largest_difference(reference);
    EXPECT_LT(translation, 1e-6);
    EXPECT_LT(rotation, 1e-6);
    char text[64];
    std::snprintf(text, sizeof(text), "%.3g m, %.3g rad", translation, rotation);
    ::testing::Test::RecordProperty("largest_difference_from_run_sequence", text);
    for (std::size_t i = 0; i < reference.size(); ++i) {
      const auto it = recording.mapped.find(drive.clouds[i].header.stamp);
      if (it == recording.mapped.end()) continue;
      const double t = (it->second.translation() - reference[i].translation()).norm();
      if (t < 1e-6) continue;
      ADD_FAILURE() << "the first scan off run_sequence's pose: " << i << ", by " << t << " m";
      break;
    }
  }
};

class Drive : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { run_.play(); }
  void SetUp() override { ASSERT_TRUE(run_.graph_ready) << "the nodes did not come up"; }
  static inline PlayedDrive run_;
};

TEST_F(Drive, EveryScanIsMapped) {
  run_.expect_every_scan_mapped();
}

TEST_F(Drive, SamePosesAsRunSequenceOnTheSameBag) {
  run_.expect_run_sequences_poses();
}

TEST_F(Drive, BothInputsTookPartAsOffline) {
  ASSERT_TRUE(run_.saw_final_counts) << sensor_value(run_.recording, "IMU scans used");
  const nlohmann::json& sensors = run_.summary["motion_sensors"];
  EXPECT_GT(sensors["imu"]["scans_used"].get<long>(), 0);
  EXPECT_GT(sensors["wheel_odometry"]["scans_used"].get<long>(), 0);
  for (const char* input : {"imu", "wheel_odometry"}) {
    const std::string name = std::string(input) == "imu" ? "IMU" : "wheel odometry";
    EXPECT_EQ(sensor_value(run_.recording, name + " scans used"),
              std::to_string(sensors[input]["scans_used"].get<long>()))
        << input;
    EXPECT_EQ(sensor_value(run_.recording, name + " samples accepted"),
              std::to_string(sensors[input]["accepted"].get<long>()))
        << input;
    EXPECT_EQ(sensor_value(run_.recording, name + " topic"),
              std::string(input) == "imu" ? "/imu/data" : "/odom");
  }
  EXPECT_EQ(sensor_value(run_.recording, "scans without mapping feedback (total)"), "0");
}

TEST_F(Drive, MapOptimizationPairsTheMotionPriors) {
  const std::string mapping_node = param("mapping_node");
  EXPECT_EQ(
      std::count(run_.priors_subscribers.begin(), run_.priors_subscribers.end(), mapping_node), 1)
      << mapping_node;
}

// The follow test's holds (~follow_test: the tunnel drive, the others have it off) as the offline
// run's: with the poses the same, map_optimization held what run_sequence's scan-to-map held.
TEST_F(Drive, TheOdometryHeldTheScansRunSequenceHeld) {
  const long held = run_.summary["odometry_held_scans"].get<long>();
  if (!ros::NodeHandle("~").param("follow_test", false)) {
    EXPECT_EQ(held, 0);
    return;
  }
  EXPECT_GT(held, 0) << "a bare tunnel the follow test does not hold in";
  ASSERT_TRUE(run_.saw_final_counts) << sensor_value(run_.recording, "IMU scans used");
  EXPECT_EQ(sensor_value(run_.recording, "scans held along their travel (follow test, total)"),
            std::to_string(held));
}

// The bag's /tf_static (lidar_sim's) looked up as feature_association looks it up and turned into
// the config's angles: the sensors.yaml lidar_sim wrote for the same drive.
TEST_F(Drive, TheExtrinsicsFromTfAreTheSimulatorsSensorsYaml) {
  tf2::BufferCore buffer;
  for (const geometry_msgs::TransformStamped& transform : run_.drive.static_transforms.transforms)
    buffer.setTransform(transform, "bag", true);
  const Config yaml = load_config(
      std::vector<std::string>{std::string(CONFIG_DIR) + "/vlp16.yaml", param("sensors_yaml")});
  const auto expect_pose = [&](const std::string& child, const std::vector<double>& rpy_deg,
                               const std::vector<double>& xyz_m) {
    const Eigen::Isometry3d from_tf =
        tf2::transformToEigen(buffer.lookupTransform("velodyne", child, ros::Time(0)));
    std::vector<double> rpy, xyz;
    ros_bridge::set_extrinsic(from_tf, rpy, xyz);
    const Eigen::Isometry3d as_config = pose_from_rpy_xyz(rpy.data(), xyz.data());
    const Eigen::Isometry3d in_yaml = pose_from_rpy_xyz(rpy_deg.data(), xyz_m.data());
    EXPECT_LT((as_config.matrix() - in_yaml.matrix()).cwiseAbs().maxCoeff(), 1e-9) << child;
  };
  expect_pose("imu", yaml.imu.extrinsic_rpy_deg, yaml.imu.extrinsic_xyz_m);
  expect_pose("base_link", yaml.wheel_odometry.extrinsic_rpy_deg,
              yaml.wheel_odometry.extrinsic_xyz_m);
  EXPECT_EQ(sensor_value(run_.recording, "IMU extrinsic"), "TF velodyne -> imu");
  EXPECT_EQ(sensor_value(run_.recording, "wheel odometry extrinsic"), "TF velodyne -> base_link");
}

TEST_F(Drive, TheGravityArrowPointsUpInTheSensorFrame) {
  const auto& markers = run_.recording.gravity_markers;
  ASSERT_FALSE(markers.empty()) << "no /gravity_marker while subscribed";
  int arrows = 0;
  for (const auto& [stamp, marker] : markers) {
    if (marker.action != visualization_msgs::Marker::ADD) continue;
    ++arrows;
    EXPECT_EQ(marker.header.frame_id, "velodyne");
    ASSERT_EQ(marker.points.size(), 2u);
    const Eigen::Vector3d up(marker.points[1].x, marker.points[1].y, marker.points[1].z);
    // On a level road the sensor's z axis is up, within its rolling and pitching.
    EXPECT_GT(up.normalized().z(), std::cos(10.0 * M_PI / 180.0)) << stamp;
  }
  EXPECT_GE(arrows, run_.summary["motion_sensors"]["imu"]["scans_used"].get<int>());
}

class Faults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    run_.play();
    clean_ = read_kitti_poses(param("clean_reference") + "/poses_kitti.txt");
    const std::string sensors_yaml = param("sensors_yaml");
    truth_ = read_kitti_poses(sensors_yaml.substr(0, sensors_yaml.rfind('/')) + "/poses.txt");
  }
  void SetUp() override { ASSERT_TRUE(run_.graph_ready) << "the nodes did not come up"; }
  static inline PlayedDrive run_;
  static inline std::vector<Eigen::Isometry3d> clean_;
  static inline std::vector<Eigen::Isometry3d> truth_;
};

// The largest translation and rotation differences between two trajectories from pose `from` on.
std::pair<double, double> largest_difference(const std::vector<Eigen::Isometry3d>& a,
                                             const std::vector<Eigen::Isometry3d>& b,
                                             std::size_t from) {
  double translation = 0.0, rotation = 0.0;
  for (std::size_t i = from; i < a.size() && i < b.size(); ++i) {
    translation = std::max(translation, (a[i].translation() - b[i].translation()).norm());
    rotation = std::max(rotation, angle_between(a[i], b[i]));
  }
  return {translation, rotation};
}

TEST_F(Faults, TheRunCompletes) {
  run_.expect_every_scan_mapped();
}

// Each fault is dropped where the offline run drops it: the same samples reach the core.
TEST_F(Faults, SamePosesAsRunSequenceOnTheSameBag) {
  run_.expect_run_sequences_poses();
}

TEST_F(Faults, DiagnosticsCountEachFaultAsSummaryJson) {
  ASSERT_TRUE(run_.saw_final_counts) << sensor_value(run_.recording, "IMU scans used");
  const nlohmann::json& sensors = run_.summary["motion_sensors"];
  for (const char* input : {"imu", "wheel_odometry"}) {
    const std::string name = std::string(input) == "imu" ? "IMU" : "wheel odometry";
    for (const char* kind : {"not finite", "out of order", "repeated stamp", "beyond limits"}) {
      const long count = sensors[input]["faults"][kind].get<long>();
      EXPECT_GE(count, 1) << input << " " << kind << ": the bag should have one";
      EXPECT_EQ(sensor_value(run_.recording, name + " dropped: " + kind), std::to_string(count))
          << input << " " << kind;
    }
    EXPECT_EQ(sensor_value(run_.recording, name + " scans LiDAR-only"),
              std::to_string(sensors[input]["scans_lidar_only"].get<long>()))
        << input;
  }
  EXPECT_EQ(sensor_value(run_.recording, "IMU gaps (total)"),
            std::to_string(sensors["imu"]["gaps"].get<long>()));
  EXPECT_EQ(sensors["imu"]["gaps"].get<long>(), 1);
  EXPECT_EQ(sensor_value(run_.recording, "IMU restarts"),
            std::to_string(sensors["imu"]["restarts"].get<long>()));
  EXPECT_GE(sensors["imu"]["restarts"].get<long>(), 1);
  // The scans in the IMU's gap went on after the timeout.
  EXPECT_NE(sensor_value(run_.recording, "scans processed on the sensor timeout (total)"), "0");
}

TEST_F(Faults, EachFaultIsLoggedOncePerInputAndKind) {
  for (const char* input : {"IMU sample at", "wheel odometry sample at"}) {
    for (const char* kind : {"not finite", "out of order", "repeated stamp", "beyond limits"}) {
      int lines = 0;
      for (const std::string& line : run_.recording.warnings) {
        lines += line.rfind("feature_association: ", 0) == 0 &&
                 line.find(input) != std::string::npos &&
                 line.find(std::string("dropped: ") + kind) != std::string::npos;
      }
      EXPECT_EQ(lines, 1) << input << " " << kind;
    }
  }
}

TEST_F(Faults, DiagnosticsWarnWhileTheImuIsOut) {
  bool warned = false;
  for (const diagnostic_msgs::DiagnosticStatus& status : run_.recording.diagnostics_history) {
    if (status.name != kFeatureAssociation) continue;
    warned |= status.level == diagnostic_msgs::DiagnosticStatus::WARN &&
              status.message.find("IMU fell back to LiDAR-only") != std::string::npos;
  }
  EXPECT_TRUE(warned);
  EXPECT_EQ(sensor_value(run_.recording, "IMU in use"), "yes") << "the IMU should be back";
}

// After the IMU came back and its filter started again, the drive is as close to the truth as
// the fault-free drive's run: what the faults cost does not last. (Both runs are 0.3-0.5 m off
// the truth from the first scans on, as the LiDAR alone is: the first sweeps are not de-skewed.)
TEST_F(Faults, AfterTheFaultsTheDriveIsAsCloseToTheTruthAsWithoutThem) {
  ASSERT_EQ(clean_.size(), run_.drive.clouds.size());
  ASSERT_EQ(truth_.size(), run_.drive.clouds.size());
  const std::size_t last = truth_.size() - 5;
  const auto [error, rotation_error] = run_.largest_difference(truth_);
  const auto [clean_error, clean_rotation_error] = largest_difference(clean_, truth_, 0);
  const auto [last_error, last_rotation_error] = run_.largest_difference(truth_, last);
  const auto [clean_last_error, clean_last_rotation_error] =
      largest_difference(clean_, truth_, last);
  char text[96];
  std::snprintf(text, sizeof(text), "%.3g m, %.3g deg (fault-free %.3g m, %.3g deg)", last_error,
                last_rotation_error * 180.0 / M_PI, clean_last_error,
                clean_last_rotation_error * 180.0 / M_PI);
  RecordProperty("largest_error_over_the_last_five_scans", text);
  EXPECT_LT(error, clean_error + 0.05);
  EXPECT_LT(rotation_error, clean_rotation_error + 0.3 * M_PI / 180.0);
  EXPECT_LT(last_error, clean_last_error + 0.02);
  EXPECT_LT(last_rotation_error, clean_last_rotation_error + 0.2 * M_PI / 180.0);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "motion_sensors_checker");
  ros::NodeHandle nh;  // keeps the node up for the whole run
  return RUN_ALL_TESTS();
}
