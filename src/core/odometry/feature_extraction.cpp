#include "adaptive_lego_loam/core/odometry/feature_extraction.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {
namespace {

constexpr int kNeighbours = 5;  // on each side, for smoothness and blocking

}  // namespace

void FeatureSet::clear() {
  // Fresh clouds, not cleared ones: the odometry and keyframes keep the previous scan's.
  for (CloudPtr* cloud : {&sharp, &less_sharp, &flat, &less_flat, &outliers}) {
    cloud->reset(new Cloud);
  }
}

FeatureExtractor::FeatureExtractor(const FeatureParams& params) : params_(params) {}

void FeatureExtractor::compute_curvature(const SegmentedCloud& cloud) {
  const std::vector<float>& range = cloud.info.range;
  const int size = static_cast<int>(range.size());
  curvature_.assign(size, 0.f);
  for (int i = kNeighbours; i + kNeighbours < size; ++i) {
    float difference = -2.f * kNeighbours * range[i];
    for (int j = 1; j <= kNeighbours; ++j)
      difference += range[i - j] + range[i + j];
    curvature_[i] = difference * difference;
  }
}

void FeatureExtractor::mark_unreliable(const SegmentedCloud& cloud) {
  const std::vector<float>& range = cloud.info.range;
  const std::vector<uint32_t>& column = cloud.info.column;
  const int size = static_cast<int>(range.size());
  picked_.assign(size, 0);
  const float occlusion = static_cast<float>(params_.occlusion_threshold);
  const float parallel = static_cast<float>(params_.parallel_threshold);
  for (int i = kNeighbours; i + kNeighbours + 1 < size; ++i) {
    const float here = range[i], next = range[i + 1];
    const int column_gap = std::abs(int(column[i + 1]) - int(column[i]));
    if (column_gap < 10) {
      // Of two neighbours far apart in range, the far side is partly hidden behind the near one.
      if (here - next > occlusion) {
        std::fill(picked_.begin() + i - kNeighbours, picked_.begin() + i + 1, 1);
      } else if (next - here > occlusion) {
        std::fill(picked_.begin() + i + 1, picked_.begin() + i + kNeighbours + 2, 1);
      }
    }
    // A surface seen nearly edge-on: the range jumps on both sides.
    const float before = std::fabs(range[i - 1] - here), after = std::fabs(next - here);
    if (before > parallel * here && after > parallel * here) picked_[i] = 1;
  }
}

void FeatureExtractor::block_neighbours(const SegmentedCloud& cloud, int index) {
  const std::vector<uint32_t>& column = cloud.info.column;
  const int size = static_cast<int>(column.size());
  picked_[index] = 1;
  for (int step : {1, -1}) {
    for (int j = 1; j <= kNeighbours; ++j) {
      const int other = index + step * j, previous = index + step * (j - 1);
      if (other < 0 || other >= size) break;
      if (std::abs(int(column[other]) - int(column[previous])) > 10) break;
      picked_[other] = 1;
    }
  }
}

void FeatureExtractor::pick_row(const SegmentedCloud& cloud, int row, FeatureSelection& out) {
  const int start = cloud.info.start_ring_index[row], end = cloud.info.end_ring_index[row];
  if (end - start < params_.sectors) return;
  for (int sector = 0; sector < params_.sectors; ++sector) {
    const int first = (start * (params_.sectors - sector) + end * sector) / params_.sectors;
    const int last =
        (start * (params_.sectors - 1 - sector) + end * (sector + 1)) / params_.sectors - 1;
    if (last <= first) continue;
    edge_candidates_.clear();
    flat_candidates_.clear();
    for (int i = first; i <= last; ++i) {
      if (cloud.info.ground_flag[i]) {
        if (curvature_[i] < params_.surface_threshold)
          flat_candidates_.push_back({curvature_[i], i});
      } else if (curvature_[i] > params_.edge_threshold) {
        edge_candidates_.push_back({curvature_[i], i});
      }
    }
    // The index breaks ties: equal curvatures pick the same points every run.
    auto by_curvature = [](const Smoothness& a, const Smoothness& b) {
      return a.value < b.value || (a.value == b.value && a.index < b.index);
    };
    std::sort(edge_candidates_.begin(), edge_candidates_.end(), by_curvature);
    std::sort(flat_candidates_.begin(), flat_candidates_.end(), by_curvature);

    int edges = 0;
    for (auto it = edge_candidates_.rbegin(); it != edge_candidates_.rend(); ++it) {
      const int i = it->index;
      if (picked_[i]) continue;
      if (++edges > params_.less_sharp_per_sector) break;
      label_[i] = edges <= params_.sharp_per_sector ? 2 : 1;
      if (label_[i] == 2) out.sharp.push_back({i, row});
      out.less_sharp.push_back({i, row});
      block_neighbours(cloud, i);
    }

    int flats = 0;
    for (const Smoothness& candidate : flat_candidates_) {
      const int i = candidate.index;
      if (picked_[i]) continue;
      label_[i] = -1;
      out.flat.push_back({i, row});
      block_neighbours(cloud, i);
      if (++flats >= params_.flat_per_sector) break;
    }
    for (int i = first; i <= last; ++i) {
      if (label_[i] <= 0) out.less_flat.push_back({i, row});
    }
  }
  out.group_ends.push_back(out.less_flat.size());
}

void FeatureExtractor::extract(const SegmentedCloud& cloud, const std::vector<ScanPoint>& points,
                               const std::vector<ScanPoint>& outliers, FeatureSet& out) {
  select(cloud, selection_);
  assemble(selection_, points, outliers, out);
}

void FeatureExtractor::select(const SegmentedCloud& cloud, FeatureSelection& out) {
  Stopwatch watch;
  for (std::vector<FeatureSelection::Pick>* picks :
       {&out.sharp, &out.less_sharp, &out.flat, &out.less_flat})
    picks->clear();
  out.group_ends.clear();
  compute_curvature(cloud);
  mark_unreliable(cloud);
  label_.assign(cloud.info.range.size(), 0);
  const int rows = static_cast<int>(cloud.info.start_ring_index.size());
  for (int row = 0; row < rows; ++row)
    pick_row(cloud, row, out);
  out.ms = watch.elapsed_ms();
}

void FeatureExtractor::assemble(const FeatureSelection& selection,
                                const std::vector<ScanPoint>& points,
                                const std::vector<ScanPoint>& outliers, FeatureSet& out) {
  out.clear();
  const auto add = [&points](const std::vector<FeatureSelection::Pick>& picks, Cloud& cloud) {
    for (const FeatureSelection::Pick& pick : picks)
      cloud.push_back(to_cloud_point(points[pick.index], static_cast<float>(pick.row)));
  };
  add(selection.sharp, *out.sharp);
  add(selection.less_sharp, *out.less_sharp);
  add(selection.flat, *out.flat);
  // Room for as many as the last scan had: the cloud grows row by row, and each reallocation
  // of a large block costs fresh pages.
  out.less_flat->reserve(less_flat_capacity_);
  std::size_t begin = 0;
  for (const std::size_t end : selection.group_ends) {
    row_less_flat_.clear();
    for (std::size_t k = begin; k < end; ++k) {
      const FeatureSelection::Pick& pick = selection.less_flat[k];
      row_less_flat_.push_back(to_cloud_point(points[pick.index], static_cast<float>(pick.row)));
    }
    *out.less_flat += *voxel_filter_(row_less_flat_, params_.less_flat_voxel);
    begin = end;
  }
  for (const ScanPoint& p : outliers)
    out.outliers->push_back(to_cloud_point(p, -1.0f));
  less_flat_capacity_ = out.less_flat->size() + out.less_flat->size() / 8;
}

}  // namespace adaptive_lego_loam
