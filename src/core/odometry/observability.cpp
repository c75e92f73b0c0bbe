#include "adaptive_lego_loam/core/odometry/observability.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>

namespace adaptive_lego_loam {
namespace {

// Below this information (1/m^2 or 1/rad^2: a sigma of 10 km or rad) a direction is free.
constexpr double kFree = 1e-8;

void principal(const Eigen::Matrix3d& covariance, Eigen::Vector3d& sigma,
               Eigen::Matrix3d& directions) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(0.5 *
                                                        (covariance + covariance.transpose()));
  // Ascending variance: take the columns from the last, largest sigma first.
  for (int k = 0; k < 3; ++k) {
    const double variance = solver.eigenvalues()(2 - k);
    sigma(k) = variance < 1.0 / kFree / 2.0 ? std::sqrt(std::max(variance, 0.0)) : INFINITY;
    directions.col(k) = solver.eigenvectors().col(2 - k);
  }
}

}  // namespace

Observability observability(const Eigen::Matrix<double, 6, 6>& information) {
  // Regularised by the free level: a direction with no information gets a 10 km sigma, which
  // reads as infinite, and everything coupled to it follows.
  const Eigen::Matrix<double, 6, 6> covariance =
      (information + kFree * Eigen::Matrix<double, 6, 6>::Identity()).inverse();
  Observability out;
  principal(covariance.bottomRightCorner<3, 3>(), out.translation_sigma,
            out.translation_directions);
  principal(covariance.topLeftCorner<3, 3>(), out.rotation_sigma, out.rotation_directions);
  return out;
}

Eigen::Matrix<double, 6, 6> discounted_along(const Eigen::Matrix<double, 6, 6>& information,
                                             const Eigen::Vector3d& direction, double keep) {
  Eigen::Matrix<double, 6, 6> scale = Eigen::Matrix<double, 6, 6>::Identity();
  scale.bottomRightCorner<3, 3>() += (keep - 1.0) * direction * direction.transpose();
  return scale * information * scale;
}

Eigen::Vector3d held_along(const Eigen::Vector3d& translation, const Eigen::Vector3d& held,
                           const Eigen::Vector3d& direction) {
  return translation + direction.dot(held - translation) * direction;
}

Eigen::Matrix<double, 6, 6> covariance_from_information(
    const Eigen::Matrix<double, 6, 6>& information, double unknown_variance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(
      0.5 * (information + information.transpose()));
  Eigen::Matrix<double, 6, 1> variances;
  for (int k = 0; k < 6; ++k) {
    const double value = solver.eigenvalues()(k);
    variances(k) = value * unknown_variance > 1.0 ? 1.0 / value : unknown_variance;
  }
  return solver.eigenvectors() * variances.asDiagonal() * solver.eigenvectors().transpose();
}

}  // namespace adaptive_lego_loam
