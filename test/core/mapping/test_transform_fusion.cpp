// LeGO-LOAM's transform fusion: the odometry's pose corrected by mapping's, and its covariance:
// mapping's at the mapped scan, growing by what the odometry's grew since.

#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/mapping/transform_fusion.h"

using namespace adaptive_lego_loam;

namespace {

Eigen::Isometry3d pose_at(double x, double y, double yaw_rad) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, 0.0);
  return pose;
}

}  // namespace

TEST(TransformFusion, TheOdometryIsCorrectedByMappingsLastPose) {
  TransformFusion fusion;
  const Eigen::Isometry3d odometry = pose_at(10.0, 0.0, 0.0);
  const Eigen::Isometry3d mapped = pose_at(10.5, 0.3, 0.02);
  fusion.update_mapping(odometry, mapped);
  EXPECT_TRUE(fusion.fuse(odometry).isApprox(mapped, 1e-12));
  const Eigen::Isometry3d step = pose_at(1.0, 0.0, 0.0);
  EXPECT_TRUE(fusion.fuse(odometry * step).isApprox(mapped * step, 1e-12));
}

TEST(TransformFusion, TheCovarianceIsMappingsGrownByTheOdometrysSince) {
  TransformFusion fusion;
  const Eigen::Isometry3d odometry = pose_at(10.0, 0.0, 0.0);
  Matrix6d odometry_covariance = Matrix6d::Identity() * 0.5;  // drifted: large
  // Before mapping: the odometry's own.
  EXPECT_TRUE(
      fusion.fused_covariance(odometry, odometry_covariance).isApprox(odometry_covariance, 1e-12));

  const Matrix6d map_covariance = Matrix6d::Identity() * 1e-4;
  fusion.update_mapping(odometry, odometry_covariance, pose_at(10.5, 0.3, 0.02), map_covariance);
  EXPECT_TRUE(
      fusion.fused_covariance(odometry, odometry_covariance).isApprox(map_covariance, 1e-12))
      << "at the mapped scan: mapping's";

  // One scan on, the odometry added a step's covariance: so does the fused pose, on mapping's.
  const Eigen::Isometry3d step = pose_at(1.0, 0.0, 0.0);
  const Matrix6d step_covariance = Matrix6d::Identity() * 2e-5;
  const Matrix6d later = compose_covariance(odometry_covariance, step, step_covariance);
  EXPECT_TRUE(fusion.fused_covariance(odometry * step, later)
                  .isApprox(compose_covariance(map_covariance, step, step_covariance), 1e-9));
}
