#include "adaptive_lego_loam/core/odometry/deskew.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {
namespace {

bool time_field_usable(const std::vector<ScanPoint>& points, bool has_time, double scan_period,
                       float& earliest) {
  if (!has_time || points.empty()) return false;
  float latest = -INFINITY;
  earliest = INFINITY;
  for (const ScanPoint& p : points) {
    if (!std::isfinite(p.time)) continue;
    earliest = std::min(earliest, p.time);
    latest = std::max(latest, p.time);
  }
  const double span = latest - earliest;
  return span >= 0.5 * scan_period && span <= 1.5 * scan_period;
}

}  // namespace

bool sweep_fractions(const std::vector<ScanPoint>& points, bool has_time, double start_azimuth,
                     double scan_period, std::vector<float>& fractions) {
  fractions.resize(points.size());
  float earliest = 0.f;
  if (time_field_usable(points, has_time, scan_period, earliest)) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      fractions[i] =
          std::clamp(static_cast<float>((points[i].time - earliest) / scan_period), 0.f, 1.f);
    }
    return true;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Clockwise: the azimuth falls as the sweep goes on.
    double turned = start_azimuth - std::atan2(points[i].y, points[i].x);
    turned -= 2.0 * M_PI * std::floor(turned / (2.0 * M_PI));
    fractions[i] = static_cast<float>(turned / (2.0 * M_PI));
  }
  return false;
}

Eigen::Isometry3d interpolate_motion(const Eigen::Isometry3d& motion, double s) {
  // The shortest-arc angle and axis of the rotation: turning by s times the angle is its slerp
  // from the identity.
  const Eigen::AngleAxisd rotation(Eigen::Quaterniond(motion.linear()));
  Eigen::Isometry3d partial = Eigen::Isometry3d::Identity();
  partial.linear() = Eigen::AngleAxisd(s * rotation.angle(), rotation.axis()).toRotationMatrix();
  partial.translation() = s * motion.translation();
  return partial;
}

void deskew_to_sweep_end(const Eigen::Isometry3d& sweep_motion, const std::vector<float>& fractions,
                         std::vector<ScanPoint>& points) {
  const Eigen::Isometry3d end_from_start = sweep_motion.inverse();
  // interpolate_motion per point, with the angle and axis found once.
  const Eigen::AngleAxisd rotation(Eigen::Quaterniond(sweep_motion.linear()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    ScanPoint& p = points[i];
    const double s = fractions[i];
    const Eigen::Matrix3d partial =
        Eigen::AngleAxisd(s * rotation.angle(), rotation.axis()).toRotationMatrix();
    const Eigen::Vector3d moved = end_from_start * (partial * Eigen::Vector3d(p.x, p.y, p.z) +
                                                    s * sweep_motion.translation());
    p.x = static_cast<float>(moved.x());
    p.y = static_cast<float>(moved.y());
    p.z = static_cast<float>(moved.z());
  }
}

}  // namespace adaptive_lego_loam
