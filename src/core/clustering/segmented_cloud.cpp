#include "adaptive_lego_loam/core/clustering/segmented_cloud.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {

void build_segmented_cloud(const RangeImage& image, const std::vector<uint8_t>& ground,
                           const ClusterLabels& clusters, const SegmentationParams& params,
                           int ground_rows, SegmentedCloud& out) {
  out.points.clear();
  out.row.clear();
  out.outliers.clear();
  out.ground.clear();
  CloudInfo& info = out.info;
  info.start_ring_index.assign(image.rows(), 0);
  info.end_ring_index.assign(image.rows(), 0);
  info.ground_flag.clear();
  info.column.clear();
  info.range.clear();

  for (int row = 0; row < image.rows(); ++row) {
    // LeGO-LOAM leaves 5 points at each end of a row out of feature extraction.
    info.start_ring_index[row] = static_cast<int32_t>(out.points.size()) - 1 + 5;
    for (int col = 0; col < image.cols(); ++col) {
      const int cell = image.cell(row, col);
      if (!image.occupied(cell)) continue;
      const bool is_ground = ground[cell] != 0;
      if (is_ground) {
        out.ground.push_back(image.point(cell));
        if (col % params.ground_downsample != 0) continue;
      } else if (clusters.label[cell] == ClusterLabels::kNone) {
        continue;
      } else if (!clusters.point_kept(cell)) {
        if (row > ground_rows && col % params.outlier_downsample == 0) {
          out.outliers.push_back(image.point(cell));
        }
        continue;
      }
      out.points.push_back(image.point(cell));
      out.row.push_back(static_cast<uint16_t>(row));
      info.ground_flag.push_back(is_ground);
      info.column.push_back(static_cast<uint32_t>(col));
      info.range.push_back(image.range(cell));
    }
    info.end_ring_index[row] = static_cast<int32_t>(out.points.size()) - 1 - 5;
  }
}

void sweep_orientation(const Scan& scan, CloudInfo& info) {
  auto valid = [](const ScanPoint& p) { return std::isfinite(p.x) && std::isfinite(p.y); };
  const auto first = std::find_if(scan.points.begin(), scan.points.end(), valid);
  if (first == scan.points.end()) {
    info.start_orientation = info.end_orientation = 0.f;
    info.orientation_diff = 2.f * float(M_PI);
    return;
  }
  const auto last = std::find_if(scan.points.rbegin(), scan.points.rend(), valid);
  float start = -std::atan2(first->y, first->x);
  float end = -std::atan2(last->y, last->x) + 2.f * float(M_PI);
  if (end - start > 3.f * float(M_PI)) {
    end -= 2.f * float(M_PI);
  } else if (end - start < float(M_PI)) {
    end += 2.f * float(M_PI);
  }
  info.start_orientation = start;
  info.end_orientation = end;
  info.orientation_diff = end - start;
}

}  // namespace adaptive_lego_loam
