#pragma once
// docs/METHOD.md, step 3: depth clustering (Bogoslavskyi & Stachniss), the clusters of LeGO-LOAM's
// labelComponents: cells joined over the 4 direct neighbours, columns wrapping.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/cluster_labels.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

// The angle criterion: with d1 >= d2 the two ranges and alpha the angle between their beams,
// beta = atan2(d2 sin(alpha), d1 - d2 cos(alpha)); the points join when beta > beta0.
// beta = atan2(y, x) with y = d2 sin(alpha) > 0, so beta > beta0 (beta0 in (0, pi/2)) is
// cot(beta) < cot(beta0), i.e. x sin(beta0) < y cos(beta0): no trigonometry per pair.
inline bool depth_points_join(float range_a, float range_b, float sin_alpha, float cos_alpha,
                              float sin_beta0, float cos_beta0) {
  const float d1 = range_a > range_b ? range_a : range_b;
  const float d2 = range_a > range_b ? range_b : range_a;
  return (d1 - d2 * cos_alpha) * sin_beta0 < d2 * sin_alpha * cos_beta0;
}

class DepthClustering {
 public:
  explicit DepthClustering(const RangeImageGeometry& geometry);
  // Clusters the occupied, not excluded cells of `image` with threshold beta0 (degrees) and
  // marks which clusters `rule` keeps. `excluded` (one flag per cell, may be empty) holds cells
  // that take no part, e.g. ground.
  void cluster(const RangeImage& image, const std::vector<uint8_t>& excluded, double beta0_deg,
               const ClusterSizeRule& rule, ClusterLabels& out);
  // cluster() again on the image and excluded cells of the last call, with another beta0. When it
  // is no stricter, every pair that joined still joins: only the pairs that newly join are
  // linked into the last call's clusters (the ambient filter's step 9 after step 5).
  void recluster(const RangeImage& image, double beta0_deg, const ClusterSizeRule& rule,
                 ClusterLabels& out);

 private:
  RangeImageGeometry geometry_;
  std::vector<float> sin_row_gap_, cos_row_gap_;  // between row r and r + 1
  float sin_col_step_ = 0.f, cos_col_step_ = 0.f;

  // The criterion is symmetric, so the breadth-first search's clusters are the connected
  // components of the joining neighbour pairs. They are found in two row-major passes over a
  // union-find forest instead, which ids them in the same order (by their first cell) without a
  // queue. Buffers are kept to reuse their memory between scans.
  void find_joins(const RangeImage& image, double beta0_deg);
  void link_joined_cells(int rows, int cols);
  void link_new_joins(int rows, int cols);
  void label_components(int cols, const ClusterSizeRule& rule, ClusterLabels& out);

  // Flags of joins_: which neighbours a cell joins (each pair is flagged once).
  static constexpr uint8_t kJoinsLeft = 1, kJoinsUp = 2, kJoinsFirstColumn = 4;
  std::vector<uint8_t> member_;  // per cell: occupied and not excluded
  std::vector<uint8_t> joins_;   // per cell
  std::vector<uint8_t> previous_joins_;
  double beta0_deg_ = 0.0;       // of the last call
  std::vector<int32_t> parent_;  // per member cell: a cell of its cluster no later than itself
  std::vector<int32_t> last_row_, rows_spanned_;  // per cluster
};

}  // namespace adaptive_lego_loam
