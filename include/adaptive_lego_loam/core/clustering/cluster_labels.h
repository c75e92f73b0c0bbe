#pragma once
// What every clustering of the range image produces: a cluster id per cell, and which clusters
// their size rule keeps.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

// Cluster labels over a range image, shared by every clustering in the core.
struct ClusterLabels {
  static constexpr int32_t kNone = 0;  // empty, or excluded (ground)
  std::vector<int32_t> label;          // per cell: kNone or a cluster id >= 1
  std::vector<int32_t> size;           // per cluster id (entry 0 unused)
  std::vector<uint8_t> kept;           // per cluster id: 1 when the cluster passed its size rule

  int clusters() const { return static_cast<int>(size.size()) - 1; }
  bool point_kept(int cell) const { return label[cell] != kNone && kept[label[cell]]; }
  int kept_clusters() const;
  int kept_points() const;
};

// LeGO-LOAM's rule: at least min_points, or at least min_points_multi_row spanning min_rows rows.
inline bool size_rule_keeps(const ClusterSizeRule& rule, int size, int rows_spanned) {
  return size >= rule.min_points ||
         (size >= rule.min_points_multi_row && rows_spanned >= rule.min_rows);
}

// Marks kept[] for every cluster of `labels` by `rule`, counting the rows each cluster spans.
void apply_size_rule(const RangeImage& image, const ClusterSizeRule& rule, ClusterLabels& labels);

}  // namespace adaptive_lego_loam
