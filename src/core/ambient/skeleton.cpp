#include "adaptive_lego_loam/core/ambient/skeleton.h"

namespace adaptive_lego_loam {

int extract_skeleton(const ClusterLabels& euclidean, const ClusterLabels& depth,
                     std::vector<uint8_t>& skeleton) {
  const int cells = static_cast<int>(euclidean.label.size());
  skeleton.assign(cells, 0);
  int count = 0;
  // point_kept() of both, without branches: kept or not is close to a coin toss cell by cell.
  const int32_t* euclidean_label = euclidean.label.data();
  const int32_t* depth_label = depth.label.data();
  const uint8_t* euclidean_kept = euclidean.kept.data();
  const uint8_t* depth_kept = depth.kept.data();
  uint8_t* flag = skeleton.data();
  for (int cell = 0; cell < cells; ++cell) {
    const int32_t e = euclidean_label[cell], d = depth_label[cell];
    flag[cell] = (e != ClusterLabels::kNone) & (euclidean_kept[e] != 0) &
                 (d != ClusterLabels::kNone) & (depth_kept[d] != 0);
    count += flag[cell];
  }
  return count;
}

}  // namespace adaptive_lego_loam
