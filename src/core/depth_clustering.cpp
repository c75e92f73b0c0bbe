#include "adaptive_lego_loam/core/depth_clustering.h"

#include <algorithm>
#include <cmath>

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

DepthClustering::DepthClustering(const RangeImageGeometry& geometry)
    : geometry_(geometry),
      sin_col_step_(std::sin(geometry.col_step_rad)),
      cos_col_step_(std::cos(geometry.col_step_rad)) {
  for (int row = 0; row + 1 < geometry_.rows; ++row) {
    const double gap = geometry_.row_gap_rad(row, row + 1);
    sin_row_gap_.push_back(std::sin(gap));
    cos_row_gap_.push_back(std::cos(gap));
  }
}

void DepthClustering::cluster(const RangeImage& image, const std::vector<uint8_t>& excluded,
                              double beta0_deg, const ClusterSizeRule& rule, ClusterLabels& out) {
  const int rows = image.rows(), cols = image.cols();
  const double beta0 = beta0_deg * M_PI / 180.0;
  const float sin_beta0 = static_cast<float>(std::sin(beta0));
  const float cos_beta0 = static_cast<float>(std::cos(beta0));
  out.label.assign(image.size(), ClusterLabels::kNone);
  out.size.assign(1, 0);
  out.kept.assign(1, 0);
  queue_.resize(image.size());
  // One byte per cell: still free to join a cluster (occupied, not excluded, not yet labelled).
  free_.resize(image.size());
  for (int cell = 0; cell < image.size(); ++cell) {
    free_[cell] = image.occupied(cell) && (excluded.empty() || !excluded[cell]);
  }
  row_seen_.assign(rows, 0);
  int32_t* label = out.label.data();
  uint8_t* is_free = free_.data();

  for (int seed = 0; seed < image.size(); ++seed) {
    if (!is_free[seed]) continue;
    const int32_t id = static_cast<int32_t>(out.size.size());
    label[seed] = id;
    is_free[seed] = 0;
    int head = 0, tail = 0;
    queue_[tail++] = {seed, seed / cols, seed % cols};
    while (head < tail) {
      const QueuedCell current = queue_[head++];
      const int cell = current.cell, row = current.row, col = current.col;
      const float range = image.range(cell);
      // Branch-free: whether a neighbour joins is close to a coin toss on foliage.
      auto visit = [&](int neighbour, int neighbour_row, int neighbour_col, float sin_alpha,
                       float cos_alpha) {
        const bool joins =
            is_free[neighbour] && depth_points_join(range, image.range(neighbour), sin_alpha,
                                                    cos_alpha, sin_beta0, cos_beta0);
        label[neighbour] = joins ? id : label[neighbour];
        is_free[neighbour] &= !joins;
        queue_[tail] = {neighbour, neighbour_row, neighbour_col};
        tail += joins;
      };
      if (row > 0) visit(cell - cols, row - 1, col, sin_row_gap_[row - 1], cos_row_gap_[row - 1]);
      if (row + 1 < rows) visit(cell + cols, row + 1, col, sin_row_gap_[row], cos_row_gap_[row]);
      if (col > 0) {
        visit(cell - 1, row, col - 1, sin_col_step_, cos_col_step_);
      } else {
        visit(cell + cols - 1, row, cols - 1, sin_col_step_, cos_col_step_);
      }
      if (col + 1 < cols) {
        visit(cell + 1, row, col + 1, sin_col_step_, cos_col_step_);
      } else {
        visit(cell - cols + 1, row, 0, sin_col_step_, cos_col_step_);
      }
    }
    out.size.push_back(tail);
    out.kept.push_back(passes(rule, tail));
  }
}

// Counts rows only for clusters too small to pass on size alone.
bool DepthClustering::passes(const ClusterSizeRule& rule, int size) {
  if (size >= rule.min_points) return true;
  if (size < rule.min_points_multi_row) return false;
  int rows_spanned = 0;
  for (int i = 0; i < size; ++i) {
    uint8_t& seen = row_seen_[queue_[i].row];
    rows_spanned += !seen;
    seen = 1;
  }
  for (int i = 0; i < size; ++i)
    row_seen_[queue_[i].row] = 0;
  return rows_spanned >= rule.min_rows;
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
    const int size = labels.size[id];
    labels.kept[id] = size >= rule.min_points ||
                      (size >= rule.min_points_multi_row && rows_spanned[id] >= rule.min_rows);
  }
}

}  // namespace adaptive_lego_loam
