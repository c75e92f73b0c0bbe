#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
namespace fs = std::filesystem;

namespace {

const std::string kSeq07 = std::string(TEST_DATA_DIR) + "/kitti_seq07";

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Poses with irrational-looking numbers, so that a lossy format would show.
std::vector<Eigen::Isometry3d> winding_poses() {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 6; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = (Eigen::AngleAxisd(0.37 * i, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(0.011 * i, Eigen::Vector3d(1, 2, 3).normalized()))
                        .toRotationMatrix();
    pose.translation() << 1.0 / 3.0 * i, -std::sqrt(2.0) * i, 1e-7 * i;
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace

TEST(KittiPoses, ReadsSequence07GroundTruth) {
  const auto poses = read_kitti_poses(kSeq07 + "/poses.txt");
  ASSERT_EQ(poses.size(), 5u);
  EXPECT_TRUE(poses[0].isApprox(Eigen::Isometry3d::Identity(), 1e-9));
  EXPECT_DOUBLE_EQ(poses[4].translation().z(), 0.38731);
  EXPECT_DOUBLE_EQ(poses[4].matrix()(0, 2), -0.03008212);
  EXPECT_DOUBLE_EQ(poses[2].matrix()(1, 3), -0.004359704);
}

TEST(KittiPoses, RoundTripIsExactAndDeterministic) {
  const auto poses = winding_poses();
  const std::string path = temp_path("round_trip_kitti.txt");
  write_kitti_poses(path, poses);
  const auto back = read_kitti_poses(path);
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i)
    EXPECT_TRUE(back[i].matrix() == poses[i].matrix()) << "pose " << i;
  const std::string first_write = read_text(path);
  write_kitti_poses(path, back);
  EXPECT_EQ(read_text(path), first_write);
}

TEST(KittiPoses, WritesShortestNumbers) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() << 0.5, -2, 0.1;
  const std::string path = temp_path("identity.txt");
  write_kitti_poses(path, {Eigen::Isometry3d::Identity(), pose});
  EXPECT_EQ(read_text(path), "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0.5 0 1 0 -2 0 0 1 0.1\n");
}

TEST(KittiPoses, ShortLineNamesFileLineAndCounts) {
  const std::string path =
      write_text("short_line.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n\n1 0 0 0 0 1 0 0 0 0 1\n");
  const std::string error = error_of([&] { read_kitti_poses(path); });
  EXPECT_EQ(error, path + ":3: expected 12 numbers, found 11");
}

TEST(KittiPoses, TumLineGetsAHint) {
  const std::string path = write_text("tum_as_kitti.txt", "0 1 2 3 0 0 0 1\n");
  const std::string error = error_of([&] { read_kitti_poses(path); });
  EXPECT_NE(error.find(path + ":1: expected 12 numbers, found 8"), std::string::npos) << error;
  EXPECT_NE(error.find("TUM"), std::string::npos) << error;
}

TEST(KittiPoses, RejectsTextNonFiniteAndNonRotations) {
  const std::string text = write_text("text.txt", "1 0 0 0 0 1 0 0 0 0 1 x0\n");
  EXPECT_EQ(error_of([&] { read_kitti_poses(text); }), text + ":1: expected a number, found 'x0'");
  const std::string nan =
      write_text("nan.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 nan 0 1 0 0 0 0 1 0\n");
  EXPECT_EQ(error_of([&] { read_kitti_poses(nan); }), nan + ":2: number 4 is not finite ('nan')");
  const std::string inf = write_text("inf.txt", "1 0 0 0 0 1 0 0 0 0 1 -inf\n");
  EXPECT_NE(error_of([&] { read_kitti_poses(inf); }).find(":1: number 12 is not finite"),
            std::string::npos);
  const std::string scaled = write_text("scaled.txt", "2 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_NE(error_of([&] { read_kitti_poses(scaled); }).find(":1: the 3x3 rotation block is not"),
            std::string::npos);
  const std::string mirrored = write_text("mirrored.txt", "-1 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_NE(error_of([&] { read_kitti_poses(mirrored); }).find("not a rotation"),
            std::string::npos);
}

TEST(KittiPoses, MissingFileAndEmptyFile) {
  EXPECT_EQ(error_of([] { read_kitti_poses("/nonexistent/poses.txt"); }),
            "/nonexistent/poses.txt: cannot open");
  EXPECT_TRUE(read_kitti_poses(write_text("empty.txt", "")).empty());
}

TEST(TumPoses, RoundTripWithPositiveQw) {
  auto poses = winding_poses();
  // Over a half turn: Eigen computes its quaternion with qw < 0.
  poses[3].linear() =
      Eigen::AngleAxisd(3.5, Eigen::Vector3d(0.2, 1, 0.4).normalized()).toRotationMatrix();
  std::vector<double> times;
  for (std::size_t i = 0; i < poses.size(); ++i)
    times.push_back(1317384506.40 + 0.1 * i);
  const std::string path = temp_path("round_trip_tum.txt");
  write_tum_poses(path, times, poses);
  const StampedPoses back = read_tum_poses(path);
  ASSERT_EQ(back.poses.size(), poses.size());
  EXPECT_EQ(back.times, times);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_TRUE(back.poses[i].translation() == poses[i].translation()) << "pose " << i;
    EXPECT_LT((back.poses[i].linear() - poses[i].linear()).cwiseAbs().maxCoeff(), 1e-14);
  }
  std::istringstream lines(read_text(path));
  std::string line;
  while (std::getline(lines, line)) {
    const double qw = std::stod(line.substr(line.rfind(' ') + 1));
    EXPECT_GE(qw, 0.0) << line;
  }
}

TEST(TumPoses, ReadsCommentsAndNormalisesQuaternions) {
  const std::string path = write_text(
      "tum.txt", "# timestamp tx ty tz qx qy qz qw\n0.5 1 2 3 0 0 0 2\n0.6 1 2 3 0 0 3 3\n");
  const StampedPoses stamped = read_tum_poses(path);
  ASSERT_EQ(stamped.poses.size(), 2u);
  EXPECT_EQ(stamped.times[1], 0.6);
  EXPECT_TRUE(stamped.poses[0].linear().isApprox(Eigen::Matrix3d::Identity(), 1e-15));
  const Eigen::Matrix3d yaw_90 =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(stamped.poses[1].linear().isApprox(yaw_90, 1e-15));
  EXPECT_EQ(stamped.poses[1].translation(), Eigen::Vector3d(1, 2, 3));
}

TEST(TumPoses, ErrorsNameFileAndLine) {
  const std::string zero = write_text("zero_q.txt", "# header\n0.5 1 2 3 0 0 0 0\n");
  EXPECT_EQ(error_of([&] { read_tum_poses(zero); }), zero + ":2: quaternion (qx qy qz qw) is zero");
  const std::string kitti = kSeq07 + "/poses.txt";
  EXPECT_NE(
      error_of([&] { read_tum_poses(kitti); }).find(kitti + ":1: expected 8 numbers, found 12"),
      std::string::npos);
  EXPECT_NE(error_of([] {
              write_tum_poses(temp_path("x.txt"), {0.0}, {});
            }).find("1 timestamps for 0 poses"),
            std::string::npos);
}

TEST(KittiCalib, ReadsTrOfSequence07) {
  const Eigen::Isometry3d tr = read_kitti_calib_tr(kSeq07 + "/calib.txt");
  EXPECT_DOUBLE_EQ(tr.matrix()(0, 1), -9.999659513510e-01);
  EXPECT_DOUBLE_EQ(tr.translation().z(), -3.339968064433e-01);
  EXPECT_DOUBLE_EQ(tr.matrix()(2, 0), 9.999773098287e-01);
}

TEST(KittiCalib, SkipsProjectionLinesAndNamesErrors) {
  const std::string p_line = "P0: 7.18e+02 0 6.07e+02 0 0 7.18e+02 1.85e+02 0 0 0 1 0\n";
  const std::string full =
      write_text("calib_full.txt",
                 p_line + p_line + p_line + p_line + "Tr: 0 -1 0 0.1 0 0 -1 0.2 1 0 0 0.3\n");
  const Eigen::Isometry3d tr = read_kitti_calib_tr(full);
  EXPECT_EQ(tr.translation(), Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(tr.linear() * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());

  const std::string no_tr = write_text("calib_no_tr.txt", p_line);
  EXPECT_NE(error_of([&] { read_kitti_calib_tr(no_tr); }).find(no_tr + ": no 'Tr:' line"),
            std::string::npos);
  const std::string short_tr =
      write_text("calib_short.txt", p_line + "Tr: 1 0 0 0 0 1 0 0 0 0 1\n");
  EXPECT_EQ(error_of([&] { read_kitti_calib_tr(short_tr); }),
            short_tr + ":2: expected 12 numbers, found 11 after 'Tr:'");
}

TEST(KittiTimes, ReadsSequence07AndRejectsTwoNumbers) {
  const std::vector<double> times = read_kitti_times(kSeq07 + "/times.txt");
  ASSERT_EQ(times.size(), 5u);
  EXPECT_EQ(times[0], 0.0);
  EXPECT_EQ(times[4], 0.415622);
  const std::string path = write_text("times_bad.txt", "0\n0.1 0.2\n");
  EXPECT_EQ(error_of([&] { read_kitti_times(path); }),
            path + ":2: expected 1 number (a timestamp), found 2");
}

TEST(PoseFiles, ParseTwinsReadTextAndNameTheSource) {
  const auto poses = parse_kitti_poses("1 0 0 2 0 1 0 3 0 0 1 4\n", "bag:/poses");
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].translation().z(), 4.0);
  EXPECT_EQ(parse_kitti_times("0.5\n\n1.5\n", "times").back(), 1.5);
  EXPECT_EQ(parse_tum_poses("# t x y z qx qy qz qw\n2 1 1 1 0 0 0 1\n", "tum").times[0], 2.0);
  EXPECT_EQ(parse_kitti_calib_tr("Tr: 1 0 0 9 0 1 0 0 0 0 1 0\n", "calib").translation().x(), 9.0);
  EXPECT_EQ(error_of([] { parse_kitti_times("1 2\n", "mem/times.txt"); }),
            "mem/times.txt:1: expected 1 number (a timestamp), found 2");
}

TEST(TumPoses, HugeQuaternionIsNormalisedNotZeroed) {
  // (qx qy qz qw) = (1e200, 0, 0, 0): a half turn about x, as (1, 0, 0, 0) is.
  const StampedPoses stamped = parse_tum_poses("0 1 2 3 1e200 0 0 0\n", "tum.txt");
  ASSERT_EQ(stamped.poses.size(), 1u);
  EXPECT_TRUE(
      stamped.poses[0].linear().isApprox(Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix()))
      << stamped.poses[0].linear();
}
