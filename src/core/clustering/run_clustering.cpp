#include "adaptive_lego_loam/core/clustering/run_clustering.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/clustering/union_find.h"

namespace adaptive_lego_loam {
namespace {

float squared_distance(const ScanPoint& a, const ScanPoint& b) {
  const float dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

RunClustering::RunClustering(const RangeImageGeometry& geometry, const RunClusteringParams& params)
    : geometry_(geometry), params_(params) {}

void RunClustering::find_runs(const RangeImage& image) {
  if (row_cells_.empty()) return;
  const float run_squared = static_cast<float>(params_.run_threshold * params_.run_threshold);
  int32_t run = static_cast<int32_t>(parent_.size());
  parent_.push_back(run);
  run_of_[row_cells_.front()] = run;
  for (std::size_t i = 1; i < row_cells_.size(); ++i) {
    const int cell = row_cells_[i];
    if (squared_distance(image.point(row_cells_[i - 1]), image.point(cell)) >= run_squared) {
      run = static_cast<int32_t>(parent_.size());
      parent_.push_back(run);
    }
    run_of_[cell] = run;
  }
  // The row is a ring: its last point follows its first.
  const int first = row_cells_.front(), last = row_cells_.back();
  if (first != last && squared_distance(image.point(first), image.point(last)) < run_squared) {
    union_find_unite(parent_, run_of_[first], run_of_[last]);
  }
}

int RunClustering::merge_half_window(float horizontal_range) const {
  const double threshold = params_.merge_threshold;
  if (horizontal_range <= threshold) return geometry_.cols;
  // A point within th_merge differs in azimuth by at most asin(th_merge / r); one column more
  // for the floor of the column index and one for a point displaced to a neighbouring column.
  const double half_angle = std::asin(threshold / horizontal_range);
  return std::min(geometry_.cols,
                  static_cast<int>(std::ceil(half_angle / geometry_.col_step_rad)) + 2);
}

void RunClustering::merge_with_row_above(const RangeImage& image) {
  if (above_cells_.empty() || row_cells_.empty()) return;
  const int cols = geometry_.cols;
  const int above_start = above_cells_.front() - image.col_of(above_cells_.front());
  const float merge_squared = static_cast<float>(params_.merge_threshold * params_.merge_threshold);
  // The nearest point above among the cells of columns [lo, hi] (inside the row).
  auto nearest_in = [&](const ScanPoint& p, int lo, int hi, float& best_squared, int& best_cell) {
    auto it = std::lower_bound(above_cells_.begin(), above_cells_.end(), above_start + lo);
    for (; it != above_cells_.end() && *it <= above_start + hi; ++it) {
      const float d = squared_distance(p, image.point(*it));
      if (d < best_squared) {
        best_squared = d;
        best_cell = *it;
      }
    }
  };
  for (const int cell : row_cells_) {
    const ScanPoint& p = image.point(cell);
    const int col = image.col_of(cell);
    const int half = merge_half_window(std::sqrt(p.x * p.x + p.y * p.y));
    float best_squared = merge_squared;
    int best_cell = -1;
    if (2 * half + 1 >= cols) {
      nearest_in(p, 0, cols - 1, best_squared, best_cell);
    } else if (col - half < 0) {
      nearest_in(p, col - half + cols, cols - 1, best_squared, best_cell);
      nearest_in(p, 0, col + half, best_squared, best_cell);
    } else if (col + half >= cols) {
      nearest_in(p, col - half, cols - 1, best_squared, best_cell);
      nearest_in(p, 0, col + half - cols, best_squared, best_cell);
    } else {
      nearest_in(p, col - half, col + half, best_squared, best_cell);
    }
    if (best_cell >= 0) union_find_unite(parent_, run_of_[cell], run_of_[best_cell]);
  }
}

void RunClustering::cluster(const RangeImage& image, const std::vector<uint8_t>& excluded,
                            ClusterLabels& out) {
  const int cols = image.cols();
  parent_.clear();
  run_of_.assign(image.size(), -1);
  above_cells_.clear();
  for (int row = image.rows() - 1; row >= 0; --row) {
    row_cells_.clear();
    for (int cell = row * cols; cell < (row + 1) * cols; ++cell) {
      if (image.occupied(cell) && (excluded.empty() || !excluded[cell])) row_cells_.push_back(cell);
    }
    find_runs(image);
    merge_with_row_above(image);
    // An empty row ends the chain: the paper merges only with the adjacent scan line.
    std::swap(row_cells_, above_cells_);
  }

  // Number the union-find roots 1, 2, ... in the order their first cell comes.
  out.label.assign(image.size(), ClusterLabels::kNone);
  out.size.assign(1, 0);
  std::vector<int32_t> id_of_root(parent_.size(), ClusterLabels::kNone);
  for (int cell = 0; cell < image.size(); ++cell) {
    if (run_of_[cell] < 0) continue;
    int32_t& id = id_of_root[union_find_root(parent_, run_of_[cell])];
    if (id == ClusterLabels::kNone) {
      id = static_cast<int32_t>(out.size.size());
      out.size.push_back(0);
    }
    out.label[cell] = id;
    ++out.size[id];
  }
  out.kept.assign(out.size.size(), 0);
  for (std::size_t id = 1; id < out.size.size(); ++id)
    out.kept[id] = out.size[id] >= params_.min_points;
}

}  // namespace adaptive_lego_loam
