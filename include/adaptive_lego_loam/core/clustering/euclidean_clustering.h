#pragma once
// docs/METHOD.md, step 4: Euclidean clustering on the range image. Breadth-first search over a
// (2w+1) x (2w+1) window, columns wrapping; a seed A and a neighbour B join when
// |AB| < d0 = gamma * sin(alpha) * |OB|, alpha the angle between their beams, so the threshold
// grows with range (the paper's text), or, with the range-difference criterion, when
// |r_A - r_B| < gamma * alpha * r_A (the authors' published code). With a fixed threshold
// instead of d0 it is the paper's "CCL-based Euclidean clustering" baseline.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/cluster_labels.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

struct EuclideanClusteringParams {
  int window = 3;                // w
  double gamma = 1.2;            // slack over the beam spacing for range noise
  double fixed_threshold = 0.0;  // m; > 0 replaces the adaptive d0 (baseline)
  int min_points = 1;            // clusters smaller than this are not kept
  EuclideanCriterion criterion = EuclideanCriterion::kDistance;
};

class EuclideanClustering {
 public:
  EuclideanClustering(const RangeImageGeometry& geometry, const EuclideanClusteringParams& params);
  // Clusters the occupied cells not flagged in `excluded` (may be empty).
  void cluster(const RangeImage& image, const std::vector<uint8_t>& excluded, ClusterLabels& out);

  // The adaptive threshold between the beams of (row, col) and (row + row_step, col + col_step):
  // on |AB| at the neighbour's range `range`, or on |r_A - r_B| at the seed's; exposed for tests.
  double threshold(int row, int row_step, int col_step, double range) const;

 private:
  RangeImageGeometry geometry_;
  EuclideanClusteringParams params_;
  // Per row and window offset (row-major over the (2w+1)^2 window): (gamma sin(alpha))^2, so the
  // distance test is |AB|^2 < factor |OB|^2; or gamma alpha, so the range-difference test is
  // |r_A - r_B| < factor r_A.
  std::vector<float> factor_;
  struct QueuedCell {
    int32_t cell, row, col;
  };
  // Labels the cluster of `seed` as `id`; returns its size.
  int grow_cluster(const RangeImage& image, int seed, int32_t id, std::vector<int32_t>& labels);
  std::vector<QueuedCell> queue_;  // reused between scans
  std::vector<uint8_t> free_;      // per cell: occupied, not excluded, not labelled yet
};

}  // namespace adaptive_lego_loam
