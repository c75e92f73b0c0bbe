#include "adaptive_lego_loam/core/odometry/covariance_propagation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>

namespace adaptive_lego_loam {
namespace {

// The symmetric matrix with its eigenvalues held in [low, high].
Matrix6d clamped(const Matrix6d& covariance, double low, double high) {
  const Eigen::SelfAdjointEigenSolver<Matrix6d> solver(0.5 * (covariance + covariance.transpose()));
  const Eigen::Matrix<double, 6, 1> values = solver.eigenvalues().cwiseMax(low).cwiseMin(high);
  return solver.eigenvectors() * values.asDiagonal() * solver.eigenvectors().transpose();
}

// The pose's covariance seen from the end of `motion`: pose exp(xi) motion =
// pose motion exp(Ad(motion^-1) xi).
Matrix6d moved(const Matrix6d& covariance, const Eigen::Isometry3d& motion) {
  const Matrix6d to_end = adjoint(motion.inverse());
  return to_end * covariance * to_end.transpose();
}

}  // namespace

Matrix6d compose_covariance(const Matrix6d& pose_covariance, const Eigen::Isometry3d& motion,
                            const Matrix6d& motion_covariance, double max_variance) {
  return clamped(moved(pose_covariance, motion) + motion_covariance, 0.0, max_variance);
}

Matrix6d covariance_added(const Matrix6d& before, const Eigen::Isometry3d& motion,
                          const Matrix6d& after) {
  return clamped(after - moved(before, motion), 0.0, std::numeric_limits<double>::infinity());
}

}  // namespace adaptive_lego_loam
