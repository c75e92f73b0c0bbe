#include "adaptive_lego_loam/core/mapping/transform_fusion.h"

namespace adaptive_lego_loam {

void TransformFusion::update_mapping(const Eigen::Isometry3d& odometry_pose,
                                     const Eigen::Isometry3d& map_pose) {
  correction_ = map_pose * odometry_pose.inverse();
}

Eigen::Isometry3d TransformFusion::fuse(const Eigen::Isometry3d& odometry_pose) const {
  return correction_ * odometry_pose;
}

}  // namespace adaptive_lego_loam
