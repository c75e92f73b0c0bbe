#pragma once
// docs/METHOD.md, step 6: weighted normals of a seeded sample of skeleton points, from their
// range-image neighbourhoods (no KD-tree).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

struct NormalFeature {
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit
  float weight = 0.f;                                // ln((d_max - d_i) * N_i + 1)
  int32_t cell = -1;  // range-image cell of the sampled point (-1 when not from an image)
  int32_t neighbors = 0;
};

struct NormalParams {
  double sample_ratio = 0.1;     // p
  int window = 3;                // w
  double depth_threshold = 1.0;  // depth_0 (m): neighbours farther in range are left out
  int min_neighbors = 5;         // t_0 (the sampled point counts)
  double max_range = 100.0;      // d_max of the weight
  uint32_t seed = 1;
};

// Unit normal (eigenvector of the smallest eigenvalue of the centred covariance) of `points`;
// false when degenerate (fewer than 3 points).
bool pca_normal(const std::vector<Eigen::Vector3f>& points, Eigen::Vector3f& normal);

// The confidence weight of a normal (docs/METHOD.md step 6), never negative.
float normal_weight(double max_range, double range, int neighbors);

// Samples `sample_ratio` of the cells flagged in `sample_from` with a generator seeded by
// params.seed on every call (the same input gives the same normals); neighbourhoods take the
// occupied cells of the window not flagged in `excluded` (ground), whose range is within
// depth_threshold of the centre's.
void compute_normals(const RangeImage& image, const std::vector<uint8_t>& sample_from,
                     const std::vector<uint8_t>& excluded, const NormalParams& params,
                     std::vector<NormalFeature>& normals);

}  // namespace adaptive_lego_loam
