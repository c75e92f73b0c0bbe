#include "adaptive_lego_loam/sim/rotation_spline.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/sim/smoothing_spline.h"

namespace adaptive_lego_loam::sim {
namespace {

// Cubic Hermite basis on [0, 1] for a curve from 0 with slope m0 to `end` with slope m1 (slopes
// per unit of tau): value, first and second derivative in tau.
struct Hermite {
  double h10, h01, h11;
};

Hermite hermite(double tau, int derivative) {
  const double t2 = tau * tau, t3 = t2 * tau;
  switch (derivative) {
    case 0:
      return {t3 - 2.0 * t2 + tau, -2.0 * t3 + 3.0 * t2, t3 - t2};
    case 1:
      return {3.0 * t2 - 4.0 * tau + 1.0, -6.0 * t2 + 6.0 * tau, 3.0 * t2 - 2.0 * tau};
    default:
      return {6.0 * tau - 4.0, -12.0 * tau + 6.0, 6.0 * tau - 2.0};
  }
}

}  // namespace

Eigen::Matrix3d right_jacobian(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  const Eigen::Matrix3d k = skew(theta);
  double a, b;  // (1 - cos)/angle^2, (angle - sin)/angle^3
  if (angle < 1e-4) {
    a = 0.5 - angle * angle / 24.0;
    b = 1.0 / 6.0 - angle * angle / 120.0;
  } else {
    a = (1.0 - std::cos(angle)) / (angle * angle);
    b = (angle - std::sin(angle)) / (angle * angle * angle);
  }
  return Eigen::Matrix3d::Identity() - a * k + b * k * k;
}

RotationSpline::RotationSpline(std::vector<double> times, std::vector<Eigen::Matrix3d> rotations)
    : times_(std::move(times)), rotations_(std::move(rotations)) {
  const std::size_t n = times_.size();
  if (n < 2 || rotations_.size() != n) {
    throw std::invalid_argument("rotation spline: " + std::to_string(n) + " times for " +
                                std::to_string(rotations_.size()) +
                                " rotations; at least two expected");
  }
  Eigen::MatrixXd summed(n, 3);
  summed.row(0).setZero();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    increments_.push_back(rotation_log(rotations_[i].transpose() * rotations_[i + 1]));
    if (increments_.back().norm() > M_PI - 1e-6) {
      throw std::invalid_argument("rotation spline: rotations " + std::to_string(i) + " and " +
                                  std::to_string(i + 1) + " are half a turn apart");
    }
    summed.row(i + 1) = summed.row(i) + increments_.back().transpose();
  }
  const SmoothingSpline through_sums(times_, summed);
  for (std::size_t i = 0; i < n; ++i)
    rates_.push_back(through_sums.at(times_[i], 1));
  for (std::size_t i = 0; i + 1 < n; ++i)
    end_slopes_.push_back(right_jacobian(increments_[i]).partialPivLu().solve(rates_[i + 1]));
}

RotationSpline::State RotationSpline::at(double time) const {
  State state;
  state.angular_acceleration.setZero();
  if (time < times_.front() || time >= times_.back()) {  // turning on at the end's rate
    const bool after = time >= times_.back();
    const std::size_t end = after ? times_.size() - 1 : 0;
    state.angular_velocity = rates_[end];
    state.rotation = rotations_[end] * rotation_exp(rates_[end] * (time - times_[end]));
    return state;
  }
  const std::size_t i = static_cast<std::size_t>(
      std::upper_bound(times_.begin(), times_.end(), time) - times_.begin() - 1);
  const double span = times_[i + 1] - times_[i];
  const double tau = (time - times_[i]) / span;
  const auto theta_derivative = [&](int order) -> Eigen::Vector3d {
    const Hermite b = hermite(tau, order);
    const Eigen::Vector3d per_tau =
        b.h10 * span * rates_[i] + b.h01 * increments_[i] + b.h11 * span * end_slopes_[i];
    return per_tau / std::pow(span, order);
  };
  const Eigen::Vector3d theta = theta_derivative(0), rate = theta_derivative(1);
  state.rotation = rotations_[i] * rotation_exp(theta);
  const Eigen::Matrix3d jacobian = right_jacobian(theta);
  state.angular_velocity = jacobian * rate;
  // d/dt of the Jacobian along theta's motion, by a central difference (it is smooth there).
  constexpr double kStep = 1e-6;  // s
  const Eigen::Matrix3d jacobian_rate =
      (right_jacobian(theta + kStep * rate) - right_jacobian(theta - kStep * rate)) / (2.0 * kStep);
  state.angular_acceleration = jacobian * theta_derivative(2) + jacobian_rate * rate;
  return state;
}

}  // namespace adaptive_lego_loam::sim
