#include "adaptive_lego_loam/core/motion_sensors/wheel_odometry.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/common/rotations.h"

namespace adaptive_lego_loam {
namespace {

// The share of the distance a vehicle's sideways and vertical motion may reach in the base frame
// (side slip in a turn, the body pitching over a bump), and of the yaw change the odometry's
// yaw rate may be off by (the track width's error).
constexpr double kSideSlipShare = 0.02;
constexpr double kYawScaleShare = 0.03;
constexpr double kMinDistanceSigma = 0.002;  // m
constexpr double kScaleFloor = 0.002;        // the scale is never known better than this
// The scale's drift per metre driven (its variance grows by this squared times the distance).
constexpr double kScaleDriftPerMetre = 1e-4;
constexpr double kScaleGate = 4.0;  // sigmas

double variance_or(double reported, double sigma) {
  return reported > 0.0 && std::isfinite(reported) ? reported : sigma * sigma;
}

}  // namespace

std::optional<WheelMotion> integrate_wheel(const std::deque<WheelOdometrySample>& samples,
                                           double from, double to,
                                           const WheelOdometryParams& params) {
  if (samples.empty() || samples.front().stamp > from) return std::nullopt;
  const double yaw_rate_sigma = params.yaw_rate_sigma_deg * M_PI / 180.0;
  WheelMotion out;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double next = i + 1 < samples.size() ? samples[i + 1].stamp : to;
    const double start = std::max(samples[i].stamp, from);
    const double end = std::min(next, to);
    const double dt = end - start;
    if (!(dt > 0.0)) continue;
    // Only what is known by `to` decides: the samples after it may not have arrived yet.
    if (end - samples[i].stamp > params.max_gap_s) return std::nullopt;
    const WheelOdometrySample& s = samples[i];
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.linear() = rotation_exp(s.angular_velocity * dt);
    step.translation() = s.linear_velocity * dt;
    out.motion = out.motion * step;
    out.distance += s.linear_velocity.x() * dt;
    out.distance_variance += variance_or(s.linear_x_variance, params.speed_sigma) * dt * dt;
    out.yaw_variance += variance_or(s.angular_z_variance, yaw_rate_sigma) * dt * dt;
  }
  return out;
}

MotionPrior wheel_prior(const WheelMotion& wheel, double scale, double scale_sigma,
                        const Eigen::Isometry3d& lidar_from_base) {
  Eigen::Isometry3d base_motion = wheel.motion;
  base_motion.translation() *= scale;
  const double distance = std::fabs(wheel.distance * scale);
  const double along =
      std::sqrt(scale * scale * wheel.distance_variance + std::pow(scale_sigma * distance, 2) +
                std::pow(kMinDistanceSigma, 2));
  const double across = kSideSlipShare * distance + kMinDistanceSigma;
  const double yaw = Eigen::AngleAxisd(base_motion.linear()).angle();
  const double yaw_sigma =
      std::sqrt(wheel.yaw_variance + std::pow(kYawScaleShare * yaw, 2) + std::pow(1e-4, 2));
  // Right perturbations of the base's motion: [roll, pitch, yaw, forward, left, up].
  Matrix6d base_information = Matrix6d::Zero();
  base_information(2, 2) = 1.0 / (yaw_sigma * yaw_sigma);
  base_information(3, 3) = 1.0 / (along * along);
  base_information(4, 4) = 1.0 / (across * across);
  base_information(5, 5) = 1.0 / (across * across);
  const Matrix6d to_lidar_inverse = adjoint(lidar_from_base).inverse();
  MotionPrior prior;
  prior.motion = lidar_from_base * base_motion * lidar_from_base.inverse();
  prior.information = to_lidar_inverse.transpose() * base_information * to_lidar_inverse;
  return prior;
}

bool WheelScale::add(double reported, double measured, double measured_sigma) {
  variance_ += kScaleDriftPerMetre * kScaleDriftPerMetre * std::fabs(reported);
  if (!(std::fabs(reported) > 1e-3) || !(measured_sigma > 0.0)) return false;
  // measured = scale * reported + noise; a measurement far off is a slip or a LiDAR gone wrong.
  const double innovation_variance =
      reported * reported * variance_ + measured_sigma * measured_sigma;
  const double innovation = measured - scale_ * reported;
  if (innovation * innovation > kScaleGate * kScaleGate * innovation_variance) return false;
  const double gain = variance_ * reported / innovation_variance;
  scale_ += gain * innovation;
  variance_ = std::max((1.0 - gain * reported) * variance_, kScaleFloor * kScaleFloor);
  return true;
}

double WheelScale::sigma() const {
  return std::sqrt(variance_);
}

}  // namespace adaptive_lego_loam
