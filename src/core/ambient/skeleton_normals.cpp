#include "adaptive_lego_loam/core/ambient/skeleton_normals.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

namespace adaptive_lego_loam {

bool pca_normal(const std::vector<Eigen::Vector3f>& points, Eigen::Vector3f& normal) {
  if (points.size() < 3) return false;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points)
    mean += p.cast<double>();
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d centred = p.cast<double>() - mean;
    covariance += centred * centred.transpose();
  }
  covariance /= static_cast<double>(points.size());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);
  normal = solver.eigenvectors().col(0).cast<float>();  // eigenvalues ascend
  return std::isfinite(normal.squaredNorm()) && normal.squaredNorm() > 0.5f;
}

float normal_weight(double max_range, double range, int neighbors) {
  const double margin = std::max(0.0, max_range - range);
  return static_cast<float>(std::log(margin * neighbors + 1.0));
}

void compute_normals(const RangeImage& image, const std::vector<uint8_t>& sample_from,
                     const std::vector<uint8_t>& excluded, const NormalParams& params,
                     std::vector<NormalFeature>& normals) {
  normals.clear();
  std::mt19937 generator(params.seed);
  // Accept when a raw 32-bit draw falls below p * 2^32: the same on every platform, unlike
  // std::uniform_real_distribution.
  const uint64_t accept_below = static_cast<uint64_t>(params.sample_ratio * 4294967296.0);
  const int rows = image.rows(), w = params.window;
  const float depth_threshold = static_cast<float>(params.depth_threshold);
  std::vector<Eigen::Vector3f> neighbourhood;
  neighbourhood.reserve((2 * w + 1) * (2 * w + 1));
  std::vector<int> window_cols(2 * w + 1);  // wrapped once per sample, not once per cell

  for (int cell = 0; cell < image.size(); ++cell) {
    if (!sample_from[cell]) continue;
    if (generator() >= accept_below) continue;
    const int row = image.row_of(cell), col = image.col_of(cell);
    const float centre_range = image.range(cell);
    for (int dc = -w; dc <= w; ++dc)
      window_cols[dc + w] = image.wrap_col(col + dc);
    neighbourhood.clear();
    for (int r = std::max(0, row - w); r <= std::min(rows - 1, row + w); ++r) {
      for (const int window_col : window_cols) {
        const int other = image.cell(r, window_col);
        if (!image.occupied(other) || (!excluded.empty() && excluded[other])) continue;
        if (std::fabs(image.range(other) - centre_range) >= depth_threshold) continue;
        const ScanPoint& p = image.point(other);
        neighbourhood.emplace_back(p.x, p.y, p.z);
      }
    }
    const int count = static_cast<int>(neighbourhood.size());
    if (count < params.min_neighbors) continue;
    NormalFeature feature;
    if (!pca_normal(neighbourhood, feature.normal)) continue;
    feature.weight = normal_weight(params.max_range, centre_range, count);
    feature.cell = cell;
    feature.neighbors = count;
    normals.push_back(feature);
  }
}

}  // namespace adaptive_lego_loam
