#include "adaptive_lego_loam/core/skeleton.h"

namespace adaptive_lego_loam {

int extract_skeleton(const ClusterLabels& euclidean, const ClusterLabels& depth,
                     std::vector<uint8_t>& skeleton) {
  const int cells = static_cast<int>(euclidean.label.size());
  skeleton.assign(cells, 0);
  int count = 0;
  for (int cell = 0; cell < cells; ++cell) {
    skeleton[cell] = euclidean.point_kept(cell) && depth.point_kept(cell);
    count += skeleton[cell];
  }
  return count;
}

}  // namespace adaptive_lego_loam
