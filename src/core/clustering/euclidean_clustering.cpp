#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace adaptive_lego_loam {

EuclideanClustering::EuclideanClustering(const RangeImageGeometry& geometry,
                                         const EuclideanClusteringParams& params)
    : geometry_(geometry), params_(params) {
  const int w = params_.window, width = 2 * w + 1;
  const bool by_range = params_.criterion == EuclideanCriterion::kRangeDifference;
  factor_.assign(geometry_.rows * width * width, 0.f);
  for (int row = 0; row < geometry_.rows; ++row) {
    for (int row_step = -w; row_step <= w; ++row_step) {
      if (row + row_step < 0 || row + row_step >= geometry_.rows) continue;
      for (int col_step = -w; col_step <= w; ++col_step) {
        const double factor = threshold(row, row_step, col_step, 1.0);
        const int k = (row_step + w) * width + (col_step + w);
        factor_[row * width * width + k] = static_cast<float>(by_range ? factor : factor * factor);
      }
    }
  }
}

double EuclideanClustering::threshold(int row, int row_step, int col_step, double range) const {
  // The angle between the two beams, from its vertical and horizontal parts (docs/METHOD.md step
  // 4).
  const double vertical = geometry_.row_gap_rad(row, row + row_step);
  const double horizontal = col_step * geometry_.col_step_rad;
  const double alpha = std::sqrt(vertical * vertical + horizontal * horizontal);
  if (params_.criterion == EuclideanCriterion::kRangeDifference) {
    return params_.gamma * alpha * range;
  }
  return params_.gamma * std::sin(alpha) * range;
}

namespace {

// Bit i set where flags[i] is set, for the 8 flags (each 0 or 1) from `flags` on: the multiply
// gathers byte i's low bit into bit 56 + i (no two partial products meet, so nothing carries).
uint8_t pack_flags(const uint8_t* flags) {
  uint64_t word;
  std::memcpy(&word, flags, 8);
  return static_cast<uint8_t>((word * 0x0102040810204080ull) >> 56);
}

}  // namespace

void EuclideanClustering::cluster(const RangeImage& image, const std::vector<uint8_t>& excluded,
                                  ClusterLabels& out) {
  image.mark_occupied(excluded, free_);
  free_.resize(image.size() + 8, 0);  // padded: the 8-byte reads of pack_flags stay inside
  out.label.assign(image.size(), ClusterLabels::kNone);
  out.size.assign(1, 0);
  out.kept.assign(1, 0);
  queue_.resize(image.size());
  for (int seed = 0; seed < image.size(); ++seed) {
    if (!free_[seed]) continue;
    const int size = grow_cluster(image, seed, static_cast<int32_t>(out.size.size()), out.label);
    out.size.push_back(size);
    out.kept.push_back(size >= params_.min_points);
  }
}

// Breadth-first from `seed`. The join test is not symmetric (the threshold grows with the
// neighbour's range), but a cluster is every cell reachable from the seed by joins whatever the
// order its neighbours are tried in.
int EuclideanClustering::grow_cluster(const RangeImage& image, int seed, int32_t id,
                                      std::vector<int32_t>& labels) {
  int32_t* label = labels.data();
  const int rows = image.rows(), cols = image.cols(), w = params_.window;
  const int width = 2 * w + 1;
  const bool fixed = params_.fixed_threshold > 0.0;
  const bool by_range = !fixed && params_.criterion == EuclideanCriterion::kRangeDifference;
  const float fixed_squared = static_cast<float>(params_.fixed_threshold * params_.fixed_threshold);
  const ScanPoint* points = &image.point(0);
  const float* ranges = image.ranges().data();
  uint8_t* is_free = free_.data();
  QueuedCell* queue = queue_.data();
  int head = 0, tail = 0;
  label[seed] = id;
  is_free[seed] = 0;
  queue[tail++] = {seed, seed / cols, seed % cols};
  while (head < tail) {
    const QueuedCell centre = queue[head++];
    // Copied: the byte stores below could alias the image's points for all the compiler knows.
    const float ax = points[centre.cell].x, ay = points[centre.cell].y, az = points[centre.cell].z;
    const float range_a = ranges[centre.cell];
    const float* factor = &factor_[centre.row * width * width];
    // Whether neighbour `cell` joins; `k` is its window offset.
    auto joins = [&](int cell, int k) {
      const float range_b = ranges[cell];
      if (by_range) return std::fabs(range_a - range_b) < factor[k] * range_a;
      const ScanPoint& b = points[cell];
      const float dx = ax - b.x, dy = ay - b.y, dz = az - b.z;
      const float limit = fixed ? fixed_squared : factor[k] * range_b * range_b;
      return dx * dx + dy * dy + dz * dz < limit;
    };
    auto try_join = [&](int row, int col, int k) {
      const int cell = row * cols + col;
      if (joins(cell, k)) {
        label[cell] = id;
        is_free[cell] = 0;
        queue[tail++] = {cell, row, col};
      }
    };
    const int first_row = std::max(centre.row - w, 0),
              last_row = std::min(centre.row + w, rows - 1);
    const int first_col = centre.col - w;
    if (first_col < 0 || centre.col + w >= cols) {  // the window wraps around column 0
      for (int row = first_row; row <= last_row; ++row) {
        for (int col_step = -w; col_step <= w; ++col_step) {
          const int col = image.wrap_col(centre.col + col_step);
          if (is_free[row * cols + col]) {
            try_join(row, col, (row - centre.row + w) * width + col_step + w);
          }
        }
      }
      continue;
    }
    // Most of a window is labelled once a cluster grows: gather the free flags of up to 8 x 8
    // cells into one mask and try only its set bits (the centre is labelled already).
    for (int chunk = 0; chunk < width; chunk += 8) {
      const uint8_t chunk_columns = width - chunk >= 8 ? 0xff : (1u << (width - chunk)) - 1;
      for (int group = first_row; group <= last_row; group += 8) {
        const int group_rows = std::min(8, last_row + 1 - group);
        uint64_t free_cells = 0;
        for (int r = 0; r < group_rows; ++r) {
          const uint8_t flags = pack_flags(&is_free[(group + r) * cols + first_col + chunk]);
          free_cells |= static_cast<uint64_t>(flags & chunk_columns) << (8 * r);
        }
        // Bit 8 r + c is (group + r, first_col + chunk + c), window offset k0 + r width + c.
        const int k0 = (group - centre.row + w) * width + chunk;
        while (free_cells != 0) {
          const int bit = __builtin_ctzll(free_cells);
          free_cells &= free_cells - 1;
          const int r = bit >> 3, c = bit & 7;
          try_join(group + r, first_col + chunk + c, k0 + r * width + c);
        }
      }
    }
  }
  return tail;
}

}  // namespace adaptive_lego_loam
