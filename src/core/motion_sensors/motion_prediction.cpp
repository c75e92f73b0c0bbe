#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/common/rotations.h"

namespace adaptive_lego_loam {

Eigen::Isometry3d SweepMotion::at(double s) const {
  const int intervals = static_cast<int>(end_from_fraction.size()) - 1;
  if (intervals <= 0) return Eigen::Isometry3d::Identity();
  const double position = std::clamp(s, 0.0, 1.0) * intervals;
  const int first = std::min(static_cast<int>(position), intervals - 1);
  const double w = position - first;
  const Eigen::Isometry3d& a = end_from_fraction[first];
  const Eigen::Isometry3d& b = end_from_fraction[first + 1];
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = a.linear() * rotation_exp(w * rotation_log(a.linear().transpose() * b.linear()));
  pose.translation() = (1.0 - w) * a.translation() + w * b.translation();
  return pose;
}

Matrix6d adjoint(const Eigen::Isometry3d& a_from_b) {
  const Eigen::Matrix3d& rotation = a_from_b.linear();
  Matrix6d result = Matrix6d::Zero();
  result.topLeftCorner<3, 3>() = rotation;
  result.bottomLeftCorner<3, 3>() = skew(a_from_b.translation()) * rotation;
  result.bottomRightCorner<3, 3>() = rotation;
  return result;
}

}  // namespace adaptive_lego_loam
