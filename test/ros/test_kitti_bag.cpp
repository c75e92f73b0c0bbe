// kitti_to_bag: the bag's clouds, rings, times, stamps and ground truth, reading it back, and
// the tool's command line.

#include <gtest/gtest.h>

#include "support/run_command.h"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/eval/metrics.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/ros/bag_sequence.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/kitti_bag.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;
namespace fs = std::filesystem;

namespace {

const std::string kSequence = std::string(TEST_DATA_DIR) + "/kitti_seq07";
const std::string kKittiConfig = std::string(CONFIG_DIR) + "/kitti.yaml";

class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "alego_bag_XXXXXX").string();
    path_ = mkdtemp(pattern.data());
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

KittiBagOptions options_for(const std::string& input, const std::string& output) {
  KittiBagOptions options;
  options.input = input;
  options.output = output;
  options.config_path = kKittiConfig;
  return options;
}

struct BagContents {
  std::vector<sensor_msgs::PointCloud2> clouds;
  std::vector<nav_msgs::Odometry> truth;
  std::vector<ros::Time> cloud_times;  // bag record times
};

BagContents read_bag(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  BagContents contents;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    if (const auto cloud = m.instantiate<sensor_msgs::PointCloud2>()) {
      EXPECT_EQ(m.getTopic(), "/velodyne_points");
      contents.clouds.push_back(*cloud);
      contents.cloud_times.push_back(m.getTime());
    } else if (const auto truth = m.instantiate<nav_msgs::Odometry>()) {
      EXPECT_EQ(m.getTopic(), "/ground_truth");
      contents.truth.push_back(*truth);
    }
  }
  return contents;
}

// A copy of the sequence without calib.txt (scans linked, not copied).
void partial_sequence(const fs::path& dir, bool with_calib, int poses) {
  fs::create_directories(dir);
  fs::create_directory_symlink(fs::path(kSequence) / "velodyne", dir / "velodyne");
  fs::copy_file(fs::path(kSequence) / "times.txt", dir / "times.txt");
  if (with_calib) fs::copy_file(fs::path(kSequence) / "calib.txt", dir / "calib.txt");
  std::ifstream in(fs::path(kSequence) / "poses.txt");
  std::ofstream out(dir / "poses.txt");
  std::string line;
  for (int i = 0; i < poses && std::getline(in, line); ++i)
    out << line << "\n";
}

}  // namespace

TEST(KittiBag, CloudsHaveStampsRingsAndTimesAndTheGroundTruthIsInTheLidarFrame) {
  TempDir dir;
  const KittiBagSummary summary = write_kitti_bag(options_for(kSequence, dir.file("07.bag")));
  EXPECT_EQ(summary.scans, 5);
  EXPECT_TRUE(summary.ground_truth);
  EXPECT_TRUE(summary.note.empty());

  const BagContents bag = read_bag(dir.file("07.bag"));
  ASSERT_EQ(bag.clouds.size(), 5u);
  ASSERT_EQ(bag.truth.size(), 5u);
  const std::vector<double> times = read_kitti_times(kSequence + "/times.txt");
  const auto truth = camera_to_lidar_poses(read_kitti_poses(kSequence + "/poses.txt"),
                                           read_kitti_calib_tr(kSequence + "/calib.txt"));
  const RangeProjector projector(load_config(kKittiConfig).sensor);
  for (std::size_t i = 0; i < 5; ++i) {
    const sensor_msgs::PointCloud2& cloud = bag.clouds[i];
    EXPECT_NEAR(cloud.header.stamp.toSec(), 1.0 + times[i], 1e-9);
    EXPECT_EQ(bag.cloud_times[i], cloud.header.stamp);
    EXPECT_EQ(cloud.header.frame_id, "velodyne");
    const Scan scan = from_ros(cloud, "bag");
    ASSERT_TRUE(scan.has_ring && scan.has_time);
    float earliest = 1.f, latest = -1.f;
    for (const ScanPoint& p : scan.points) {
      ASSERT_EQ(p.ring, projector.row_from_elevation(p.x, p.y, p.z));
      earliest = std::min(earliest, p.time);
      latest = std::max(latest, p.time);
    }
    EXPECT_EQ(scan.points.front().time, 0.f);
    EXPECT_GE(earliest, 0.f);
    EXPECT_LT(latest, 0.1f);
    EXPECT_GT(latest, 0.095f) << "a whole turn";

    const nav_msgs::Odometry& odometry = bag.truth[i];
    EXPECT_EQ(odometry.header.stamp, cloud.header.stamp);
    EXPECT_EQ(odometry.header.frame_id, "map");
    EXPECT_EQ(odometry.child_frame_id, "velodyne");
    // KITTI's Tr is orthonormal to ~1e-6 only; a quaternion carries the nearest rotation.
    const Eigen::Isometry3d sent = pose_from_ros(odometry.pose.pose, "gt");
    EXPECT_LT((sent.translation() - truth[i].translation()).norm(), 1e-12) << i;
    EXPECT_LT((sent.linear() - truth[i].linear()).norm(), 1e-5) << i;
  }
}

TEST(KittiBag, ReadsBackAsTheSameScansAsTheFolder) {
  TempDir dir;
  const KittiBagSummary summary = write_kitti_bag(options_for(kSequence, dir.file("07.bag")));
  const auto files = list_scan_files(kSequence + "/velodyne");
  const auto sequence = open_bag_sequence(dir.file("07.bag"), "");  // the only cloud topic
  EXPECT_EQ(sequence->size(), 5);
  long long kept = 0;
  for (const std::string& file : files) {
    const Scan original = read_kitti_bin(file);
    const std::optional<Scan> scan = sequence->next();
    ASSERT_TRUE(scan);
    // Only points outside every beam are left out, none on these scans.
    ASSERT_EQ(scan->points.size(), original.points.size());
    for (std::size_t i = 0; i < original.points.size(); ++i) {
      ASSERT_EQ(scan->points[i].x, original.points[i].x);
      ASSERT_EQ(scan->points[i].z, original.points[i].z);
      ASSERT_EQ(scan->points[i].intensity, original.points[i].intensity);
    }
    kept += static_cast<long long>(scan->points.size());
  }
  EXPECT_FALSE(sequence->next());
  EXPECT_EQ(kept, summary.points - summary.dropped_points);
}

TEST(KittiBag, SixteenOfItsRingsTrackLikeAVlp16) {
  // The VLP-16-sized input of config/kitti_16rings.yaml: the same bag, every 4th ring kept, run
  // with the VLP-16 settings, still follows the ground truth within 3 cm a frame.
  TempDir dir;
  write_kitti_bag(options_for(kSequence, dir.file("07.bag")));
  const Config config = load_config(std::string(CONFIG_DIR) + "/kitti_16rings.yaml");
  Pipeline pipeline(config);
  const auto sequence = open_bag_sequence(dir.file("07.bag"), "");
  int frames = 0;
  while (const std::optional<Scan> scan = sequence->next()) {
    const FrameResult& result = pipeline.process(*scan);
    if (frames > 0) {
      EXPECT_TRUE(result.mapping.matched) << "frame " << frames;
    }
    ++frames;
  }
  ASSERT_EQ(frames, 5);
  const auto truth = camera_to_lidar_poses(read_kitti_poses(kSequence + "/poses.txt"),
                                           read_kitti_calib_tr(kSequence + "/calib.txt"));
  const RelativePoseError rpe = relative_pose_error(pipeline.trajectory(), truth);
  for (std::size_t i = 0; i < rpe.translation_m.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i + 1));
    EXPECT_LT(rpe.translation_m[i], 0.03);
    EXPECT_LT(rpe.rotation_deg[i], 0.5);
  }
  std::printf("16 rings: RPE RMSE %.4f m per frame\n", *rpe.translation_rmse_m);
}

TEST(KittiBag, RingAndTimeOfSinglePoints) {
  SensorParams sensor;
  sensor.rows = 16;
  sensor.beam_angles_deg.clear();
  for (int row = 0; row < 16; ++row)
    sensor.beam_angles_deg.push_back(-15.0 + 2.0 * row);
  const RangeProjector projector(sensor);
  Scan scan;
  const float nan = std::nanf("");
  scan.points = {{10, 0, 0},         // azimuth 0, elevation 0: row 7 or 8 (-1 or +1 deg)
                 {0, -10, -2.6f},    // a quarter turn clockwise later, ~-14.6 deg: row 0
                 {0, 0, 10},         // straight up: outside the beams
                 {nan, 1, 1},        // not finite
                 {-10, 0, 0.175f}};  // half a turn later, 1 deg: row 8
  EXPECT_EQ(add_ring_and_time(projector, 0.1, scan), 2);
  ASSERT_EQ(scan.points.size(), 3u);
  EXPECT_TRUE(scan.has_ring && scan.has_time);
  EXPECT_EQ(scan.points[1].ring, 0);
  EXPECT_EQ(scan.points[2].ring, 8);
  EXPECT_FLOAT_EQ(scan.points[0].time, 0.f);
  EXPECT_NEAR(scan.points[1].time, 0.025f, 1e-6);
  EXPECT_NEAR(scan.points[2].time, 0.05f, 1e-6);
}

TEST(KittiBag, WithoutCalibNoGroundTruthAndANote) {
  TempDir dir;
  partial_sequence(dir.path() / "seq", false, 5);
  const KittiBagSummary summary =
      write_kitti_bag(options_for(dir.file("seq"), dir.file("out.bag")));
  EXPECT_EQ(summary.scans, 5);
  EXPECT_FALSE(summary.ground_truth);
  EXPECT_NE(summary.note.find("no calib.txt"), std::string::npos) << summary.note;
  EXPECT_TRUE(read_bag(dir.file("out.bag")).truth.empty());
}

TEST(KittiBag, FewerPosesThanScansIsAnErrorNamingThePoseFile) {
  TempDir dir;
  partial_sequence(dir.path() / "seq", true, 3);
  try {
    write_kitti_bag(options_for(dir.file("seq"), dir.file("out.bag")));
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("poses.txt: 3 poses for 5 scans"), std::string::npos)
        << e.what();
  }
}

namespace {

std::pair<int, std::string> run_tool(const std::string& arguments) {
  return adaptive_lego_loam::test::run_command(std::string(BIN_DIR) + "/kitti_to_bag " + arguments);
}

}  // namespace

TEST(KittiToBagTool, WritesTheBagAndSaysWhat) {
  TempDir dir;
  const auto [status, output] =
      run_tool("--input " + kSequence + " --output " + dir.file("07.bag"));
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("5 scans"), std::string::npos) << output;
  EXPECT_NE(output.find("ground truth on /ground_truth"), std::string::npos) << output;
  EXPECT_EQ(read_bag(dir.file("07.bag")).clouds.size(), 5u);
}

TEST(KittiToBagTool, BadInputGivesOneLineAndExitStatus1) {
  TempDir dir;
  const auto [status, output] =
      run_tool("--input " + dir.file("missing") + " --output " + dir.file("x.bag"));
  EXPECT_EQ(status, 1);
  EXPECT_EQ(output, "kitti_to_bag: " + dir.file("missing") + ": not a directory\n");
  const auto [config_status, config_output] =
      run_tool("--input " + kSequence + " --output " + dir.file("x.bag") + " --config " +
               dir.file("no.yaml"));
  EXPECT_EQ(config_status, 1);
  EXPECT_NE(config_output.find("no.yaml: cannot open config file"), std::string::npos)
      << config_output;
  const auto [help_status, help] = run_tool("--help");
  EXPECT_EQ(help_status, 0);
  EXPECT_NE(help.find("--start-time"), std::string::npos);
}
