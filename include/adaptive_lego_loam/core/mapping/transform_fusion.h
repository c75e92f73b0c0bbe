#pragma once
// LeGO-LOAM's transformFusion, the last step of the mapping stage.

#include <Eigen/Geometry>

#include "adaptive_lego_loam/core/odometry/covariance_propagation.h"

namespace adaptive_lego_loam {

// LeGO-LOAM's transformFusion: the high-rate odometry composed with the latest correction that
// mapping found (map pose = correction * odometry pose).
// Covariances (covariance_propagation.h's convention, each in its pose's frame): the fused pose's
// is mapping's carried along what the odometry's grew by since the mapped scan.
class TransformFusion {
 public:
  void update_mapping(const Eigen::Isometry3d& odometry_pose, const Eigen::Isometry3d& map_pose);
  void update_mapping(const Eigen::Isometry3d& odometry_pose, const Matrix6d& odometry_covariance,
                      const Eigen::Isometry3d& map_pose, const Matrix6d& map_covariance);
  Eigen::Isometry3d fuse(const Eigen::Isometry3d& odometry_pose) const;
  Matrix6d fused_covariance(const Eigen::Isometry3d& odometry_pose,
                            const Matrix6d& odometry_covariance) const;
  const Eigen::Isometry3d& correction() const { return correction_; }

 private:
  Eigen::Isometry3d correction_ = Eigen::Isometry3d::Identity();
  // Before the first mapped scan the odometry's own covariance is the fused pose's.
  Eigen::Isometry3d mapped_odometry_pose_ = Eigen::Isometry3d::Identity();
  Matrix6d mapped_odometry_covariance_ = Matrix6d::Zero();
  Matrix6d map_covariance_ = Matrix6d::Zero();
};

}  // namespace adaptive_lego_loam
