#pragma once
// Whether a published covariance is consistent with the error it claims: the normalised
// estimation error squared NEES = e^T P^-1 e of each scan, which for a consistent Gaussian
// estimate follows a chi-square distribution with dim(e) degrees of freedom, and the share of
// scans inside its two-sided bounds (95 %: about 95 % of a consistent estimate's scans).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace adaptive_lego_loam {

struct ChiSquareBounds {
  double lower = 0.0, upper = 0.0;
};
// The central `probability` interval of chi-square with `dof` degrees of freedom.
ChiSquareBounds chi_square_bounds(int dof, double probability = 0.95);
double chi_square_median(int dof);

// e^T P^-1 e; P symmetric positive definite (std::invalid_argument otherwise).
double nees(const Eigen::VectorXd& error, const Eigen::MatrixXd& covariance);

// The error of the scan-to-scan motion from scan a to b, estimated (P) against true (Q): the
// translation of (Q_a^-1 Q_b)^-1 (P_a^-1 P_b), in the sensor frame at b. When a's pose is right
// relative to the map this is b's error relative to the map, as a right perturbation of its pose,
// which the mapped pose's covariance describes.
Eigen::Vector3d increment_translation_error(const Eigen::Isometry3d& estimate_a,
                                            const Eigen::Isometry3d& estimate_b,
                                            const Eigen::Isometry3d& truth_a,
                                            const Eigen::Isometry3d& truth_b);

struct NeesSummary {
  int dof = 0;
  ChiSquareBounds bounds;
  int scans = 0, below = 0, within = 0, above = 0;
  std::optional<double> share_within;  // within / scans, empty without scans
  std::optional<double> median_nees;
  // The median NEES over chi-square's median: how many times too small the variances are
  // (robust to the few scans that failed outright; 1 when consistent).
  std::optional<double> variance_scale;
};

NeesSummary summarize_nees(const std::vector<double>& values, int dof, double probability = 0.95);

}  // namespace adaptive_lego_loam
