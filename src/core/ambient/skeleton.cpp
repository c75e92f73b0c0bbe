#include "adaptive_lego_loam/core/ambient/skeleton.h"

#include <cmath>

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

double fragment_smoothness(const RangeImage& image, const ClusterLabels& euclidean,
                           const std::vector<uint8_t>& skeleton, double tolerance_m) {
  int fragment_points = 0;
  int smooth_points = 0;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (skeleton[cell] || !euclidean.point_kept(cell)) continue;
    const int row = image.row_of(cell);
    const int col = image.col_of(cell);
    const int left = image.cell(row, image.wrap_col(col - 1));
    const int right = image.cell(row, image.wrap_col(col + 1));
    if (!image.occupied(left) || !image.occupied(right)) continue;
    const double second_difference =
        image.range(left) + image.range(right) - 2.0 * image.range(cell);
    ++fragment_points;
    smooth_points += std::abs(second_difference) < tolerance_m;
  }
  return fragment_points > 0 ? static_cast<double>(smooth_points) / fragment_points : 0.0;
}

}  // namespace adaptive_lego_loam
