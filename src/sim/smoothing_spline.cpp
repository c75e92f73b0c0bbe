#include "adaptive_lego_loam/sim/smoothing_spline.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam::sim {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

// Green and Silverman's band matrices of a natural cubic spline on knots spaced `h`: Q (n+1 x
// n-1) maps values to their second divided differences, R (n-1 x n-1) the second derivatives'
// roughness; the spline through g has second derivatives gamma with Q^T g = R gamma.
void band_matrices(const std::vector<double>& h, Sparse& q, Sparse& r) {
  const int n = static_cast<int>(h.size());
  std::vector<Eigen::Triplet<double>> q_entries, r_entries;
  for (int j = 1; j < n; ++j) {
    const int column = j - 1;
    q_entries.emplace_back(j - 1, column, 1.0 / h[j - 1]);
    q_entries.emplace_back(j, column, -1.0 / h[j - 1] - 1.0 / h[j]);
    q_entries.emplace_back(j + 1, column, 1.0 / h[j]);
    r_entries.emplace_back(column, column, (h[j - 1] + h[j]) / 3.0);
    if (j + 1 < n) {
      r_entries.emplace_back(column, column + 1, h[j] / 6.0);
      r_entries.emplace_back(column + 1, column, h[j] / 6.0);
    }
  }
  q.resize(n + 1, n - 1);
  q.setFromTriplets(q_entries.begin(), q_entries.end());
  r.resize(n - 1, n - 1);
  r.setFromTriplets(r_entries.begin(), r_entries.end());
}

}  // namespace

SmoothingSpline::SmoothingSpline(std::vector<double> times, const Eigen::MatrixXd& values,
                                 double cutoff_hz)
    : times_(std::move(times)) {
  const int n = static_cast<int>(times_.size()) - 1;  // segments
  if (n < 1 || values.rows() != n + 1 || values.cols() < 1) {
    throw std::invalid_argument("spline: " + std::to_string(times_.size()) + " times for " +
                                std::to_string(values.rows()) + " values; at least two expected");
  }
  if (!(cutoff_hz >= 0.0)) throw std::invalid_argument("spline: cutoff must be at least 0 Hz");
  std::vector<double> h(n);
  for (int i = 0; i < n; ++i) {
    h[i] = times_[i + 1] - times_[i];
    if (!(h[i] > 0.0)) throw std::invalid_argument("spline: times must increase");
  }
  Eigen::MatrixXd fitted = values;                                       // g
  Eigen::MatrixXd second = Eigen::MatrixXd::Zero(n + 1, values.cols());  // gamma, 0 at the ends
  if (n > 1) {
    Sparse q, r;
    band_matrices(h, q, r);
    const double lambda =
        cutoff_hz > 0.0
            ? 1.0 / ((times_.back() - times_.front()) / n * std::pow(2.0 * M_PI * cutoff_hz, 4))
            : 0.0;
    const Sparse system = r + lambda * Sparse(q.transpose() * q);
    Eigen::SimplicialLDLT<Sparse> solver(system);
    if (solver.info() != Eigen::Success) throw std::invalid_argument("spline: singular system");
    const Eigen::MatrixXd interior = solver.solve(Eigen::MatrixXd(q.transpose() * values));
    second.middleRows(1, n - 1) = interior;
    if (lambda > 0.0) fitted = values - lambda * (q * interior);
  }
  segments_.resize(n);
  for (int i = 0; i < n; ++i) {
    Eigen::MatrixX4d& s = segments_[i];
    s.resize(values.cols(), 4);
    s.col(0) = fitted.row(i).transpose();
    s.col(1) = ((fitted.row(i + 1) - fitted.row(i)) / h[i] -
                h[i] * (2.0 * second.row(i) + second.row(i + 1)) / 6.0)
                   .transpose();
    s.col(2) = 0.5 * second.row(i).transpose();
    s.col(3) = ((second.row(i + 1) - second.row(i)) / (6.0 * h[i])).transpose();
  }
  last_value_ = fitted.row(n).transpose();
  const Eigen::MatrixX4d& last = segments_.back();
  const double span = h.back();
  last_slope_ = last.col(1) + 2.0 * span * last.col(2) + 3.0 * span * span * last.col(3);
}

Eigen::VectorXd SmoothingSpline::at(double time, int derivative) const {
  if (time >= times_.back() || time < times_.front()) {  // linear beyond the ends
    const bool after = time >= times_.back();
    const Eigen::VectorXd& value = after ? last_value_ : Eigen::VectorXd(segments_.front().col(0));
    const Eigen::VectorXd slope = after ? last_slope_ : Eigen::VectorXd(segments_.front().col(1));
    const double dt = time - (after ? times_.back() : times_.front());
    if (derivative == 0) return value + dt * slope;
    if (derivative == 1) return slope;
    return Eigen::VectorXd::Zero(value.size());
  }
  const std::size_t i = static_cast<std::size_t>(
      std::upper_bound(times_.begin(), times_.end(), time) - times_.begin() - 1);
  const Eigen::MatrixX4d& s = segments_[i];
  const double dt = time - times_[i];
  switch (derivative) {
    case 0:
      return s.col(0) + dt * (s.col(1) + dt * (s.col(2) + dt * s.col(3)));
    case 1:
      return s.col(1) + dt * (2.0 * s.col(2) + 3.0 * dt * s.col(3));
    case 2:
      return 2.0 * s.col(2) + 6.0 * dt * s.col(3);
    case 3:
      return 6.0 * s.col(3);
    default:
      throw std::invalid_argument("spline: derivative " + std::to_string(derivative) +
                                  ": expected 0-3");
  }
}

Eigen::MatrixXd SmoothingSpline::knot_values() const {
  Eigen::MatrixXd values(times_.size(), last_value_.size());
  for (std::size_t i = 0; i < segments_.size(); ++i)
    values.row(i) = segments_[i].col(0).transpose();
  values.row(times_.size() - 1) = last_value_.transpose();
  return values;
}

}  // namespace adaptive_lego_loam::sim
