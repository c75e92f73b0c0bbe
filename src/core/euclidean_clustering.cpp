#include "adaptive_lego_loam/core/euclidean_clustering.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace adaptive_lego_loam {

EuclideanClustering::EuclideanClustering(const RangeImageGeometry& geometry,
                                         const EuclideanClusteringParams& params)
    : geometry_(geometry), params_(params) {
  const int w = params_.window, width = 2 * w + 1;
  squared_factor_.assign(geometry_.rows * width * width, 0.f);
  for (int row = 0; row < geometry_.rows; ++row) {
    for (int row_step = -w; row_step <= w; ++row_step) {
      if (row + row_step < 0 || row + row_step >= geometry_.rows) continue;
      for (int col_step = -w; col_step <= w; ++col_step) {
        const double factor = threshold(row, row_step, col_step, 1.0);
        const int k = (row_step + w) * width + (col_step + w);
        squared_factor_[row * width * width + k] = static_cast<float>(factor * factor);
      }
    }
  }
}

double EuclideanClustering::threshold(int row, int row_step, int col_step, double range_b) const {
  // The angle between the two beams, from its vertical and horizontal parts (METHOD.md step 4).
  const double vertical = geometry_.row_gap_rad(row, row + row_step);
  const double horizontal = col_step * geometry_.col_step_rad;
  const double alpha = std::sqrt(vertical * vertical + horizontal * horizontal);
  return params_.gamma * std::sin(alpha) * range_b;
}

void EuclideanClustering::cluster(const RangeImage& image, const std::vector<uint8_t>& excluded,
                                  ClusterLabels& out) {
  const int rows = image.rows(), cols = image.cols(), w = params_.window;
  const int width = 2 * w + 1;
  const bool fixed = params_.fixed_threshold > 0.0;
  const float fixed_squared = static_cast<float>(params_.fixed_threshold * params_.fixed_threshold);
  out.label.assign(image.size(), ClusterLabels::kNone);
  out.size.assign(1, 0);
  out.kept.assign(1, 0);
  queue_.resize(image.size());
  // Padded by a word so that the 8-byte reads below never leave the buffer.
  free_.assign(image.size() + 8, 0);
  for (int cell = 0; cell < image.size(); ++cell) {
    free_[cell] = image.occupied(cell) && (excluded.empty() || !excluded[cell]);
  }

  int32_t id = 0;
  int tail = 0;
  // Tests neighbour (row, col) of `a` against the threshold and queues it when it joins.
  auto try_join = [&](const ScanPoint& a, int row, int col, float factor) {
    const int cell = row * cols + col;
    if (!free_[cell]) return;  // also the centre, labelled before its window is searched
    const ScanPoint& b = image.point(cell);
    const float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    const float range_b = image.range(cell);
    const float limit = fixed ? fixed_squared : factor * range_b * range_b;
    if (dx * dx + dy * dy + dz * dz < limit) {
      out.label[cell] = id;
      free_[cell] = 0;
      queue_[tail++] = {cell, row, col};
    }
  };

  for (int seed = 0; seed < image.size(); ++seed) {
    if (!free_[seed]) continue;
    id = static_cast<int32_t>(out.size.size());
    out.label[seed] = id;
    free_[seed] = 0;
    int head = 0;
    tail = 0;
    queue_[tail++] = {seed, seed / cols, seed % cols};
    while (head < tail) {
      const QueuedCell current = queue_[head++];
      const ScanPoint& a = image.point(current.cell);
      const float* factor = &squared_factor_[current.row * width * width];
      const bool interior = current.col >= w && current.col + w < cols;
      for (int row_step = -w; row_step <= w; ++row_step) {
        const int row = current.row + row_step;
        if (row < 0 || row >= rows) continue;
        const float* row_factor = factor + (row_step + w) * width + w;  // indexed by col_step
        if (!interior) {  // the window wraps around column 0: cell by cell
          for (int col_step = -w; col_step <= w; ++col_step) {
            int col = current.col + col_step;
            col += col < 0 ? cols : (col >= cols ? -cols : 0);
            try_join(a, row, col, row_factor[col_step]);
          }
          continue;
        }
        // Most of a window is labelled once a cluster grows: read its free flags 8 at a time
        // and visit only the free cells.
        const int first_col = current.col - w;
        const uint8_t* window_row = &free_[row * cols + first_col];
        for (int byte = 0; byte < width; byte += 8) {
          uint64_t word;
          std::memcpy(&word, window_row + byte, 8);
          const int bytes = std::min(8, width - byte);
          if (bytes < 8) word &= (1ull << (8 * bytes)) - 1;
          while (word != 0) {
            const int offset = byte + __builtin_ctzll(word) / 8;
            word &= word - 1;  // each flag is 0 or 1: this clears that byte
            try_join(a, row, first_col + offset, row_factor[offset - w]);
          }
        }
      }
    }
    out.size.push_back(tail);
    out.kept.push_back(tail >= params_.min_points);
  }
}

}  // namespace adaptive_lego_loam
