// Each scenario generates, is deterministic, and has the character it claims; the sequence
// writer's output is what KITTI and SemanticKITTI readers expect.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "adaptive_lego_loam/sim/observability.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/sequence_writer.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/sim_requests.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

TEST(SimSequenceWriter, WritesAKittiFolder) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "alego_sim_writer_test";
  std::filesystem::remove_all(dir);
  const std::vector<SimFrame>& frames = frames_of(ScenarioKind::kUrban);
  {
    SequenceWriter writer(dir.string(), false, 0.02);
    for (int i = 0; i < kFrames; ++i)
      writer.write_frame(i, frames[i]);
    writer.finish("seed: 3\n");
  }
  const Scan scan = read_kitti_bin((dir / "velodyne" / "000001.bin").string());
  ASSERT_EQ(scan.points.size(), frames[1].scan.points.size());
  EXPECT_EQ(scan.points[10].x, frames[1].scan.points[10].x);
  EXPECT_EQ(read_labels((dir / "labels" / "000001.label").string()), frames[1].labels);
  std::ifstream poses(dir / "poses.txt");
  std::string first_line;
  std::getline(poses, first_line);
  EXPECT_EQ(first_line, kitti_pose_line(Eigen::Isometry3d::Identity()));
  const std::vector<Eigen::Isometry3d> read_back =
      adaptive_lego_loam::read_kitti_poses((dir / "poses.txt").string());
  ASSERT_EQ(read_back.size(), static_cast<std::size_t>(kFrames));
  const Eigen::Isometry3d expected = frames[0].sensor_pose.inverse() * frames[2].sensor_pose;
  EXPECT_LT((read_back[2].matrix() - expected.matrix()).norm(), 1e-6);
  EXPECT_EQ(read_kitti_times((dir / "times.txt").string()).size(),
            static_cast<std::size_t>(kFrames));
  std::ifstream calib(dir / "calib.txt");
  const std::string calib_text((std::istreambuf_iterator<char>(calib)),
                               std::istreambuf_iterator<char>());
  EXPECT_NE(calib_text.find("Tr: 1 0 0 0 0 1 0 0 0 0 1 0"), std::string::npos);
  // observability.csv: comment lines, then per scan its index and its information matrix.
  std::ifstream observability(dir / "observability.csv");
  std::string line;
  int scans = 0;
  while (std::getline(observability, line)) {
    if (line.front() == '#') continue;
    std::vector<double> fields;
    std::stringstream fields_of(line);
    for (std::string field; std::getline(fields_of, field, ',');)
      fields.push_back(std::stod(field));
    ASSERT_EQ(fields.size(), 37u) << line;
    EXPECT_EQ(fields[0], scans);
    const Information6 expected = scan_information(frames[scans], 0.02);
    for (int k = 0; k < 36; ++k)
      EXPECT_NEAR(fields[1 + k], expected(k / 6, k % 6), 1e-8 * expected.norm()) << k;
    ++scans;
  }
  EXPECT_EQ(scans, kFrames);
  // A second run into the same folder must not silently mix two sequences.
  EXPECT_THROW(SequenceWriter(dir.string(), false, 0.02), IoError);
  EXPECT_NO_THROW(SequenceWriter(dir.string(), true, 0.02));
  EXPECT_FALSE(std::filesystem::exists(dir / "velodyne" / "000001.bin"));
  EXPECT_FALSE(std::filesystem::exists(dir / "observability.csv"));
  std::filesystem::remove_all(dir);
}
