#include "adaptive_lego_loam/sim/observability.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "adaptive_lego_loam/sim/labels.h"

namespace adaptive_lego_loam::sim {
namespace {

void add_point(const Eigen::Vector3f& point, const Eigen::Vector3f& normal, Information6& sum) {
  Eigen::Matrix<double, 6, 1> jacobian;
  const Eigen::Vector3d p = point.cast<double>(), n = normal.cast<double>();
  jacobian << p.cross(n), n;
  sum.selfadjointView<Eigen::Upper>().rankUpdate(jacobian);
}

Information6 finished(Information6 sum, double sigma_m) {
  if (!(sigma_m > 0.0)) throw std::invalid_argument("observability: sigma must be positive");
  const Information6 full = sum.selfadjointView<Eigen::Upper>();
  return full / (sigma_m * sigma_m);
}

}  // namespace

Information6 point_to_plane_information(const std::vector<Eigen::Vector3f>& points,
                                        const std::vector<Eigen::Vector3f>& normals,
                                        double sigma_m) {
  if (points.size() != normals.size())
    throw std::invalid_argument("observability: as many normals as points expected");
  Information6 sum = Information6::Zero();
  for (std::size_t i = 0; i < points.size(); ++i)
    add_point(points[i], normals[i], sum);
  return finished(sum, sigma_m);
}

Information6 scan_information(const SimFrame& frame, double sigma_m) {
  if (frame.exact_points.size() != frame.labels.size() ||
      frame.exact_normals.size() != frame.labels.size())
    throw std::invalid_argument("observability: a frame without exact points for every label");
  Information6 sum = Information6::Zero();
  for (std::size_t i = 0; i < frame.labels.size(); ++i) {
    if (is_moving_class(label_class(frame.labels[i]))) continue;
    add_point(frame.exact_points[i], frame.exact_normals[i], sum);
  }
  return finished(sum, sigma_m);
}

WeakestTranslation weakest_translation(const Information6& information) {
  const Eigen::Matrix3d rotation = information.topLeftCorner<3, 3>();
  const Eigen::Matrix3d coupling = information.topRightCorner<3, 3>();
  // A rotation the scan does not fix has no coupling to the translation either (the matrix is
  // positive semi-definite): the pseudo-inverse leaves it out.
  const Eigen::Matrix3d marginal =
      information.bottomRightCorner<3, 3>() -
      coupling.transpose() *
          Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix3d>(rotation).pseudoInverse() *
          coupling;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(marginal);
  WeakestTranslation weakest;
  weakest.direction = solver.eigenvectors().col(0);
  const double least = solver.eigenvalues()(0), most = solver.eigenvalues()(2);
  weakest.sigma_m = least > 1e-12 * most && least > 0.0 ? 1.0 / std::sqrt(least)
                                                        : std::numeric_limits<double>::infinity();
  return weakest;
}

double observability_sigma(double range_noise_m) {
  return range_noise_m > 0.0 ? range_noise_m : 1.0;
}

std::string observability_header(double range_noise_m) {
  char sigma[160];
  if (range_noise_m > 0.0) {
    std::snprintf(sigma, sizeof(sigma), "%g m (the range noise)", range_noise_m);
  } else {
    std::snprintf(sigma, sizeof(sigma), "1 m (no range noise: the entries are sum_i J_i^T J_i)");
  }
  std::string header =
      "# The true observability of each scan: the 6 x 6 information matrix sum_i J_i^T J_i / "
      "sigma^2 of point-to-plane residuals of the scan's returns without range noise, with the "
      "true normals n_i of the surfaces they hit, J_i = [(p_i x n_i)^T, n_i^T].\n"
      "# Frame: the sensor at the scan's time (its pose in poses.txt). Order: rotation about x, "
      "y, z (rad), then translation along x, y, z (m); units 1/rad^2, 1/(rad m) and 1/m^2.\n"
      "# sigma: " +
      std::string(sigma) +
      ". Points on moving objects are left out; the ground counts.\n"
      "# Columns: scan index, then the 36 entries row by row (I00, I01, ..., I05, I10, ..., "
      "I55).\n";
  return header;
}

std::string observability_line(int frame, const Information6& information) {
  std::string line = std::to_string(frame);
  char number[32];
  for (int row = 0; row < 6; ++row) {
    for (int column = 0; column < 6; ++column) {
      std::snprintf(number, sizeof(number), ",%.9e", information(row, column));
      line += number;
    }
  }
  return line + "\n";
}

}  // namespace adaptive_lego_loam::sim
