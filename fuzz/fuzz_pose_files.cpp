// The trajectory readers (io/pose_files.h), each on the same input: KITTI poses, TUM poses, KITTI
// times and KITTI calib.txt. IoError is the answer to a malformed file; what a reader returns
// must keep its promises (finite numbers, rotation blocks that are rotations).

#include <Eigen/Geometry>
#include <cmath>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "fuzz_support.h"

using namespace adaptive_lego_loam;

namespace {

// The readers' tolerance for rounded text is 1e-3; normalising a quaternion is exact to ~1e-15.
void check_pose(const Eigen::Isometry3d& pose, double tolerance) {
  const Eigen::Matrix3d rotation = pose.linear();
  const double deviation =
      (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  fuzz::check(pose.matrix().allFinite(), "a pose read is finite");
  fuzz::check(deviation <= tolerance && rotation.determinant() > 0,
              "a pose read has a rotation block");
}

template <typename Parse>
void expect_io_error_or(Parse parse) {
  try {
    parse();
  } catch (const IoError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  expect_io_error_or([&] {
    for (const Eigen::Isometry3d& pose : parse_kitti_poses(text, "poses.txt"))
      check_pose(pose, 1e-3);
  });
  expect_io_error_or([&] {
    const StampedPoses stamped = parse_tum_poses(text, "tum.txt");
    fuzz::check(stamped.times.size() == stamped.poses.size(), "one time per TUM pose");
    for (std::size_t i = 0; i < stamped.poses.size(); ++i) {
      fuzz::check(std::isfinite(stamped.times[i]), "a TUM time is finite");
      check_pose(stamped.poses[i], 1e-9);
    }
  });
  expect_io_error_or([&] {
    for (double time : parse_kitti_times(text, "times.txt"))
      fuzz::check(std::isfinite(time), "a KITTI time is finite");
  });
  expect_io_error_or([&] { check_pose(parse_kitti_calib_tr(text, "calib.txt"), 1e-3); });
  return 0;
}
