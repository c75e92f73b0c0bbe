#pragma once
// LeGO-LOAM's transformFusion, the last step of the mapping stage.

#include <Eigen/Geometry>

namespace adaptive_lego_loam {

// LeGO-LOAM's transformFusion: the high-rate odometry composed with the latest correction that
// mapping found (map pose = correction * odometry pose).
class TransformFusion {
 public:
  void update_mapping(const Eigen::Isometry3d& odometry_pose, const Eigen::Isometry3d& map_pose);
  Eigen::Isometry3d fuse(const Eigen::Isometry3d& odometry_pose) const;
  const Eigen::Isometry3d& correction() const { return correction_; }

 private:
  Eigen::Isometry3d correction_ = Eigen::Isometry3d::Identity();
};

}  // namespace adaptive_lego_loam
