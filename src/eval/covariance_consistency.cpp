#include "adaptive_lego_loam/eval/covariance_consistency.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam {
namespace {

boost::math::chi_squared distribution(int dof) {
  if (dof < 1) throw std::invalid_argument("chi-square: dof must be positive");
  return boost::math::chi_squared(dof);
}

double median(std::vector<double> values) {
  const std::size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  const double upper = values[middle];
  if (values.size() % 2) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + middle));
}

}  // namespace

ChiSquareBounds chi_square_bounds(int dof, double probability) {
  if (!(probability > 0.0 && probability < 1.0))
    throw std::invalid_argument("chi-square bounds: probability must be in (0, 1)");
  const auto chi_square = distribution(dof);
  const double tail = 0.5 * (1.0 - probability);
  return {boost::math::quantile(chi_square, tail), boost::math::quantile(chi_square, 1.0 - tail)};
}

double chi_square_median(int dof) {
  return boost::math::median(distribution(dof));
}

double nees(const Eigen::VectorXd& error, const Eigen::MatrixXd& covariance) {
  if (covariance.rows() != error.size() || covariance.cols() != error.size())
    throw std::invalid_argument("nees: covariance and error differ in size");
  const Eigen::LLT<Eigen::MatrixXd> factor(covariance);
  if (factor.info() != Eigen::Success)
    throw std::invalid_argument("nees: covariance not positive definite");
  return error.dot(factor.solve(error));
}

Eigen::Vector3d increment_translation_error(const Eigen::Isometry3d& estimate_a,
                                            const Eigen::Isometry3d& estimate_b,
                                            const Eigen::Isometry3d& truth_a,
                                            const Eigen::Isometry3d& truth_b) {
  const Eigen::Isometry3d true_motion = truth_a.inverse() * truth_b;
  const Eigen::Isometry3d estimated_motion = estimate_a.inverse() * estimate_b;
  return (true_motion.inverse() * estimated_motion).translation();
}

NeesSummary summarize_nees(const std::vector<double>& values, int dof, double probability) {
  NeesSummary summary;
  summary.dof = dof;
  summary.bounds = chi_square_bounds(dof, probability);
  summary.scans = static_cast<int>(values.size());
  for (double value : values) {
    if (std::isnan(value)) throw std::invalid_argument("summarize_nees: a NEES is nan");
    if (value < summary.bounds.lower) {
      ++summary.below;
    } else if (value > summary.bounds.upper) {
      ++summary.above;
    } else {
      ++summary.within;
    }
  }
  if (values.empty()) return summary;
  summary.share_within = double(summary.within) / summary.scans;
  summary.median_nees = median(values);
  summary.variance_scale = *summary.median_nees / chi_square_median(dof);
  return summary;
}

}  // namespace adaptive_lego_loam
