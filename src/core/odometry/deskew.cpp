#include "adaptive_lego_loam/core/odometry/deskew.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/common/fast_atan2.h"

namespace adaptive_lego_loam {
namespace {

// sin(a) and 1 - cos(a); below half a radian (every sweep of a vehicle) from their series, which
// there is exact to 1e-11 and several times cheaper than sin and cos.
void turn_sine_and_versine(double a, double& sine, double& one_minus_cosine) {
  if (std::fabs(a) > 0.5) {
    sine = std::sin(a);
    one_minus_cosine = 1.0 - std::cos(a);
    return;
  }
  // Taylor coefficients: 1/3!, 1/5!, ... and 1/2!, 1/4!, ...
  constexpr double s3 = 1.0 / 6, s5 = 1.0 / 120, s7 = 1.0 / 5040, s9 = 1.0 / 362880;
  constexpr double c2 = 1.0 / 2, c4 = 1.0 / 24, c6 = 1.0 / 720, c8 = 1.0 / 40320,
                   c10 = 1.0 / 3628800;
  const double a2 = a * a;
  sine = a * (1.0 + a2 * (-s3 + a2 * (s5 + a2 * (-s7 + a2 * s9))));
  one_minus_cosine = a2 * (c2 + a2 * (-c4 + a2 * (c6 + a2 * (-c8 + a2 * c10))));
}

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
  constexpr float kTurn = 2.f * float(M_PI);
  // A point a hair before the start was fired with it (the lasers of one firing differ by about
  // that much in azimuth, fast_atan2 by 1e-5 rad), not a whole turn later.
  constexpr float kSeam = 1e-4f;
  // The start through the same approximation as the points.
  const float start = fast_atan2(static_cast<float>(std::sin(start_azimuth)),
                                 static_cast<float>(std::cos(start_azimuth)));
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Clockwise: the azimuth falls as the sweep goes on. `turned` lies in [-2 pi, 2 pi].
    float turned = start - fast_atan2(points[i].y, points[i].x);
    if (turned < -kSeam) {
      turned += kTurn;
    } else if (turned > kTurn - kSeam) {
      turned -= kTurn;
    }
    fractions[i] = std::clamp(turned / kTurn, 0.f, 1.f);
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
  // A point turned by s times the angle about the axis and moved s of the way, seen from the
  // sweep's end: E (I + sin(s angle) K + (1 - cos(s angle)) K^2) p + s E t + e, Rodrigues' formula
  // with K the axis' cross-product matrix, E and e the end's rotation and translation. In floats,
  // as the points are: 1e-7 of their range.
  const Eigen::Isometry3d end_from_start = sweep_motion.inverse();
  const Eigen::AngleAxisd rotation(Eigen::Quaterniond(sweep_motion.linear()));
  const double angle = rotation.angle();
  Eigen::Matrix3d cross;
  cross << 0.0, -rotation.axis().z(), rotation.axis().y(), rotation.axis().z(), 0.0,
      -rotation.axis().x(), -rotation.axis().y(), rotation.axis().x(), 0.0;
  const Eigen::Matrix3f end = end_from_start.linear().cast<float>();
  const Eigen::Matrix3f end_cross = (end_from_start.linear() * cross).cast<float>();
  const Eigen::Matrix3f end_cross2 = (end_from_start.linear() * cross * cross).cast<float>();
  const Eigen::Vector3f end_step =
      (end_from_start.linear() * sweep_motion.translation()).cast<float>();
  const Eigen::Vector3f end_offset = end_from_start.translation().cast<float>();
  for (std::size_t i = 0; i < points.size(); ++i) {
    ScanPoint& p = points[i];
    const float s = fractions[i];
    double sine, one_minus_cosine;
    turn_sine_and_versine(s * angle, sine, one_minus_cosine);
    const Eigen::Matrix3f turn = end + static_cast<float>(sine) * end_cross +
                                 static_cast<float>(one_minus_cosine) * end_cross2;
    const Eigen::Vector3f moved = turn * Eigen::Vector3f(p.x, p.y, p.z) + s * end_step + end_offset;
    p.x = moved.x();
    p.y = moved.y();
    p.z = moved.z();
  }
}

void deskew_to_sweep_end(const SweepMotion& sweep, const std::vector<float>& fractions,
                         std::vector<ScanPoint>& points) {
  // Each point moved by its place between two of the sweep's poses, blended linearly: the poses
  // are a few milliseconds apart, where the blend's error is far below the range noise.
  const int intervals = static_cast<int>(sweep.end_from_fraction.size()) - 1;
  if (intervals < 1) return;
  std::vector<Eigen::Matrix3f> rotations;
  std::vector<Eigen::Vector3f> translations;
  for (const Eigen::Isometry3d& pose : sweep.end_from_fraction) {
    rotations.push_back(pose.linear().cast<float>());
    translations.push_back(pose.translation().cast<float>());
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    ScanPoint& p = points[i];
    const float position = fractions[i] * intervals;
    const int first = std::min(static_cast<int>(position), intervals - 1);
    const float w = position - first;
    const Eigen::Vector3f point(p.x, p.y, p.z);
    const Eigen::Vector3f a = rotations[first] * point + translations[first];
    const Eigen::Vector3f b = rotations[first + 1] * point + translations[first + 1];
    const Eigen::Vector3f moved = (1.f - w) * a + w * b;
    p.x = moved.x();
    p.y = moved.y();
    p.z = moved.z();
  }
}

}  // namespace adaptive_lego_loam
