#include "adaptive_lego_loam/core/common/rotations.h"

#include <cmath>

namespace adaptive_lego_loam {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity() + skew(v);
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

Eigen::Vector3d rotation_log(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd angle_axis(Eigen::Quaterniond(rotation).normalized());
  return angle_axis.angle() * angle_axis.axis();
}

Eigen::Isometry3d pose_from_rpy_xyz(const double* rpy_deg, const double* xyz_m) {
  constexpr double kDeg = M_PI / 180.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(rpy_deg[2] * kDeg, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(rpy_deg[1] * kDeg, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(rpy_deg[0] * kDeg, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(xyz_m[0], xyz_m[1], xyz_m[2]);
  return pose;
}

Eigen::Isometry3d motion_in_frame(const Eigen::Isometry3d& motion_b,
                                  const Eigen::Isometry3d& a_from_b) {
  return a_from_b * motion_b * a_from_b.inverse();
}

}  // namespace adaptive_lego_loam
