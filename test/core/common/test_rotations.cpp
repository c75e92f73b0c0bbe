#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/common/rotations.h"

using namespace adaptive_lego_loam;

TEST(Rotations, ExpAndLogAreInverse) {
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(1e-13, 0, 0),
                                   Eigen::Vector3d(0.0, 3.0, 0.0)}) {
    EXPECT_LT((rotation_log(rotation_exp(v)) - v).norm(), 1e-9) << v.transpose();
  }
  EXPECT_LT((skew(Eigen::Vector3d(1, 2, 3)) * Eigen::Vector3d(-1, 0.5, 2) -
             Eigen::Vector3d(1, 2, 3).cross(Eigen::Vector3d(-1, 0.5, 2)))
                .norm(),
            1e-12);
}

TEST(Rotations, ConfigAnglesAreYawPitchRollAboutFixedAxes) {
  const double rpy[3] = {0.0, 0.0, 90.0}, xyz[3] = {0.1, -0.05, -0.2};
  const Eigen::Isometry3d pose = pose_from_rpy_xyz(rpy, xyz);
  // Yawed 90 deg: the frame's x axis points along the parent's y.
  EXPECT_LT((pose.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_EQ(pose.translation(), Eigen::Vector3d(0.1, -0.05, -0.2));
  const double upside_down[3] = {180.0, 0.0, 0.0}, origin[3] = {0, 0, 0};
  EXPECT_NEAR((pose_from_rpy_xyz(upside_down, origin).linear() * Eigen::Vector3d::UnitZ()).z(),
              -1.0, 1e-12);
}

TEST(Rotations, MotionOfARigidlyAttachedFrame) {
  // A body turning on the spot: a frame 1 m ahead of it moves on a circle.
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.linear() = rotation_exp(Eigen::Vector3d(0.0, 0.0, M_PI / 2));
  Eigen::Isometry3d ahead = Eigen::Isometry3d::Identity();
  ahead.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  const Eigen::Isometry3d motion = motion_in_frame(turn, ahead.inverse());
  EXPECT_LT((motion.translation() - Eigen::Vector3d(-1.0, 1.0, 0.0)).norm(), 1e-12);
}
