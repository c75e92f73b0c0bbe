#include "adaptive_lego_loam/core/mapping/transform_fusion.h"

namespace adaptive_lego_loam {

void TransformFusion::update_mapping(const Eigen::Isometry3d& odometry_pose,
                                     const Eigen::Isometry3d& map_pose) {
  correction_ = map_pose * odometry_pose.inverse();
}

void TransformFusion::update_mapping(const Eigen::Isometry3d& odometry_pose,
                                     const Matrix6d& odometry_covariance,
                                     const Eigen::Isometry3d& map_pose,
                                     const Matrix6d& map_covariance) {
  update_mapping(odometry_pose, map_pose);
  mapped_odometry_pose_ = odometry_pose;
  mapped_odometry_covariance_ = odometry_covariance;
  map_covariance_ = map_covariance;
}

Matrix6d TransformFusion::fused_covariance(const Eigen::Isometry3d& odometry_pose,
                                           const Matrix6d& odometry_covariance) const {
  const Eigen::Isometry3d since = mapped_odometry_pose_.inverse() * odometry_pose;
  return compose_covariance(
      map_covariance_, since,
      covariance_added(mapped_odometry_covariance_, since, odometry_covariance));
}

Eigen::Isometry3d TransformFusion::fuse(const Eigen::Isometry3d& odometry_pose) const {
  return correction_ * odometry_pose;
}

}  // namespace adaptive_lego_loam
