#include "adaptive_lego_loam/core/mapping/map_gravity.h"

namespace adaptive_lego_loam {

void MapGravity::add(const Eigen::Matrix3d& map_from_sensor, const GravityPrior& gravity) {
  if (added_ >= scans_) return;
  // Weighed by the inverse of the tilt's variance (the covariance's trace: up to 2 x the tilt's).
  const double variance = std::max(gravity.covariance.trace(), 1e-12);
  sum_ += map_from_sensor * gravity.up.normalized() / variance;
  ++added_;
}

std::optional<Eigen::Vector3d> MapGravity::up() const {
  if (added_ < scans_ || !(sum_.norm() > 0.0)) return std::nullopt;
  return sum_.normalized();
}

}  // namespace adaptive_lego_loam
