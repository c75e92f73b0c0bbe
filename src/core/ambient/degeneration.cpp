#include "adaptive_lego_loam/core/ambient/degeneration.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace adaptive_lego_loam {

Degeneration degeneration_from_normals(const std::vector<NormalFeature>& normals) {
  Degeneration result;
  result.normals = static_cast<int>(normals.size());
  Eigen::Matrix2d moment = Eigen::Matrix2d::Zero();
  for (const NormalFeature& n : normals) {
    const Eigen::Vector2d v = n.weight * n.normal.head<2>().cast<double>();
    moment += v * v.transpose();
  }
  if (!(moment.trace() > 0.0)) return result;  // no horizontal constraint at all: unknown

  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(moment);
  const Eigen::Vector2d strong = solver.eigenvectors().col(1);  // larger eigenvalue
  Eigen::Vector2d weak = solver.eigenvectors().col(0);
  double along_strong = 0.0, along_weak = 0.0;
  for (const NormalFeature& n : normals) {
    const Eigen::Vector2d v = n.weight * n.normal.head<2>().cast<double>();
    along_strong += std::fabs(v.dot(strong));
    along_weak += std::fabs(v.dot(weak));
  }
  // The direction has no sign: report it with x >= 0 (y > 0 when x = 0) so runs compare.
  if (weak.x() < 0.0 || (weak.x() == 0.0 && weak.y() < 0.0)) weak = -weak;
  result.valid = true;
  result.weak_direction = weak;
  if (along_weak <= 0.0) {
    result.k = std::numeric_limits<double>::infinity();
    result.mu = 1.0;
    return result;
  }
  result.k = std::max(1.0, along_strong / along_weak);
  result.mu = std::clamp(1.0 - 1.0 / result.k, 0.0, 1.0);
  return result;
}

double mu_with_evidence(double mu, int normals, int evidence_normals) {
  if (evidence_normals <= 0 || normals >= evidence_normals) return mu;
  const double share = static_cast<double>(std::max(normals, 0)) / evidence_normals;
  return 1.0 - (1.0 - mu) * share;
}

double structure_share(int skeleton_points, int clustered_points, double fragment_smoothness,
                       double smoothness_floor) {
  if (clustered_points <= 0) return 0.0;
  const double excess =
      smoothness_floor < 1.0
          ? std::clamp((fragment_smoothness - smoothness_floor) / (1.0 - smoothness_floor), 0.0,
                       1.0)
          : 0.0;
  const double fragments = std::max(clustered_points - skeleton_points, 0);
  return (skeleton_points + excess * fragments) / clustered_points;
}

double mu_with_structure(double mu, double share, double weight, double reference_share) {
  if (weight == 0.0) return mu;
  return std::clamp(mu + weight * (share - reference_share), 0.0, 1.0);
}

double beta0_from_mu(double mu, double beta0_min_deg, double beta0_max_deg, double mu_strict_below,
                     double mu_lenient_above) {
  if (mu <= mu_strict_below) return beta0_max_deg;
  if (mu >= mu_lenient_above) return beta0_min_deg;
  const double share = (mu - mu_strict_below) / (mu_lenient_above - mu_strict_below);
  return share * (beta0_min_deg - beta0_max_deg) + beta0_max_deg;
}

}  // namespace adaptive_lego_loam
