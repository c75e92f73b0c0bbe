#pragma once
// A natural cubic spline of a vector-valued function of time, through samples or, to take out
// noise the samples carry, the cubic smoothing spline near them (Reinsch's): twice continuously
// differentiable, so that its second derivative is an acceleration a sensor could feel.

#include <Eigen/Core>
#include <vector>

namespace adaptive_lego_loam::sim {

class SmoothingSpline {
 public:
  // `times` strictly increasing, at least two; `values` one row per time. cutoff_hz 0: the spline
  // through every value. Above 0: the smoothing spline minimising sum |value_i - f(t_i)|^2 +
  // lambda * integral |f''|^2 with lambda = 1 / (h (2 pi cutoff_hz)^4), h the mean spacing: a
  // low-pass filter that halves a sinusoid at cutoff_hz and passes slower motion. Throws
  // std::invalid_argument on bad input.
  SmoothingSpline(std::vector<double> times, const Eigen::MatrixXd& values, double cutoff_hz = 0.0);

  // The value (derivative 0) or its derivative 1, 2 or 3 at `time`. Beyond the first and last
  // time the spline goes on linearly, as a natural spline's zero second derivative there says.
  Eigen::VectorXd at(double time, int derivative = 0) const;

  const std::vector<double>& times() const { return times_; }
  // The spline's values at its times (the samples themselves when not smoothed).
  Eigen::MatrixXd knot_values() const;

 private:
  std::vector<double> times_;
  // Per segment i, one row per dimension: a, b, c, d of a + b dt + c dt^2 + d dt^3, dt = t - t_i.
  std::vector<Eigen::MatrixX4d> segments_;
  Eigen::VectorXd last_value_, last_slope_;
};

}  // namespace adaptive_lego_loam::sim
