#include "adaptive_lego_loam/core/clustering/cluster_labels.h"

namespace adaptive_lego_loam {

int ClusterLabels::kept_clusters() const {
  int count = 0;
  for (std::size_t id = 1; id < kept.size(); ++id)
    count += kept[id];
  return count;
}

int ClusterLabels::kept_points() const {
  int count = 0;
  for (std::size_t id = 1; id < kept.size(); ++id)
    count += kept[id] ? size[id] : 0;
  return count;
}

void apply_size_rule(const RangeImage& image, const ClusterSizeRule& rule, ClusterLabels& labels) {
  const int clusters = labels.clusters();
  std::vector<int32_t> last_row(clusters + 1, -1);
  std::vector<int32_t> rows_spanned(clusters + 1, 0);
  // Row-major order visits rows in increasing order, so counting row changes counts rows.
  const int32_t* label = labels.label.data();
  for (int row = 0; row < image.rows(); ++row) {
    for (int col = 0; col < image.cols(); ++col) {
      const int32_t id = *label++;
      if (id == ClusterLabels::kNone || last_row[id] == row) continue;
      last_row[id] = row;
      ++rows_spanned[id];
    }
  }
  labels.kept.assign(clusters + 1, 0);
  for (int id = 1; id <= clusters; ++id) {
    labels.kept[id] = size_rule_keeps(rule, labels.size[id], rows_spanned[id]);
  }
}

}  // namespace adaptive_lego_loam
