#include "adaptive_lego_loam/core/clustering/depth_clustering.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/core/clustering/union_find.h"

namespace adaptive_lego_loam {

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
  image.mark_occupied(excluded, member_);
  find_joins(image, beta0_deg);
  link_joined_cells(image.rows(), image.cols());
  label_components(image.cols(), rule, out);
}

void DepthClustering::recluster(const RangeImage& image, double beta0_deg,
                                const ClusterSizeRule& rule, ClusterLabels& out) {
  if (member_.size() != static_cast<std::size_t>(image.size())) {
    throw std::logic_error("DepthClustering::recluster() needs cluster() on the image first");
  }
  if (beta0_deg > beta0_deg_) {  // stricter: clusters split, start over
    find_joins(image, beta0_deg);
    link_joined_cells(image.rows(), image.cols());
  } else {
    previous_joins_.swap(joins_);
    find_joins(image, beta0_deg);
    link_new_joins(image.rows(), image.cols());
  }
  label_components(image.cols(), rule, out);
}

// Branch-free, in plain loops the compiler vectorises: whether a pair joins is close to a coin
// toss on foliage.
void DepthClustering::find_joins(const RangeImage& image, double beta0_deg) {
  beta0_deg_ = beta0_deg;
  const double beta0 = beta0_deg * M_PI / 180.0;
  const float sin_beta0 = static_cast<float>(std::sin(beta0));
  const float cos_beta0 = static_cast<float>(std::cos(beta0));
  const int rows = image.rows(), cols = image.cols();
  joins_.assign(image.size(), 0);
  const uint8_t* member = member_.data();
  const float* range = image.ranges().data();
  uint8_t* joins = joins_.data();
  const float sin_col_step = sin_col_step_, cos_col_step = cos_col_step_;
  for (int row = 0; row < rows; ++row) {
    const int first = row * cols;
    for (int cell = first + 1; cell < first + cols; ++cell) {
      joins[cell] = member[cell] & member[cell - 1] &
                    depth_points_join(range[cell], range[cell - 1], sin_col_step, cos_col_step,
                                      sin_beta0, cos_beta0);
    }
    if (row == 0) continue;
    const float sin_gap = sin_row_gap_[row - 1], cos_gap = cos_row_gap_[row - 1];
    for (int cell = first; cell < first + cols; ++cell) {
      joins[cell] |= (member[cell] & member[cell - cols] &
                      depth_points_join(range[cell], range[cell - cols], sin_gap, cos_gap,
                                        sin_beta0, cos_beta0))
                     << 1;
    }
  }
  // The columns wrap: the last cell of a row meets the first.
  for (int row = 0; row < rows && cols > 1; ++row) {
    const int first = row * cols, last = first + cols - 1;
    joins[last] |= (member[last] & member[first] &
                    depth_points_join(range[last], range[first], sin_col_step, cos_col_step,
                                      sin_beta0, cos_beta0))
                   << 2;
  }
}

void DepthClustering::link_joined_cells(int rows, int cols) {
  parent_.resize(member_.size());
  const uint8_t* member = member_.data();
  const uint8_t* joins = joins_.data();
  int32_t* parent = parent_.data();
  for (int row = 0; row < rows; ++row) {
    const int first = row * cols, last = first + cols - 1;
    for (int cell = first; cell <= last; ++cell) {
      if (!member[cell]) continue;
      // Not linked yet, the cell is its own root: joining its left neighbour hangs it under that.
      parent[cell] = joins[cell] & kJoinsLeft ? parent[cell - 1] : cell;
      if (joins[cell] & kJoinsUp) union_find_unite(parent_, cell, cell - cols);
    }
    if (joins[last] & kJoinsFirstColumn) union_find_unite(parent_, last, first);
  }
}

// The forest of the last call stays valid: the pairs that join now and did not then only merge
// its clusters. (Joins grow monotonically as beta0 falls, in float too: sin(beta0) falls,
// cos(beta0) rises and both sides of the criterion are non-negative.)
void DepthClustering::link_new_joins(int rows, int cols) {
  const uint8_t* joins = joins_.data();
  const uint8_t* previous = previous_joins_.data();
  for (int row = 0; row < rows; ++row) {
    const int first = row * cols, last = first + cols - 1;
    for (int cell = first; cell <= last; ++cell) {
      const uint8_t fresh = joins[cell] & ~previous[cell];
      if (fresh == 0) continue;
      if (fresh & kJoinsLeft) union_find_unite(parent_, cell, cell - 1);
      if (fresh & kJoinsUp) union_find_unite(parent_, cell, cell - cols);
      if (fresh & kJoinsFirstColumn) union_find_unite(parent_, last, first);
    }
  }
}

// Row-major, a cluster's first cell is its root and comes before its other cells, whose parents
// come before them too: one pass gives every cell its cluster's id and counts its rows.
void DepthClustering::label_components(int cols, const ClusterSizeRule& rule, ClusterLabels& out) {
  const int cells = static_cast<int>(member_.size());
  out.label.resize(cells);
  out.size.assign(1, 0);
  last_row_.assign(1, -1);
  rows_spanned_.assign(1, 0);
  const uint8_t* member = member_.data();
  const int32_t* parents = parent_.data();
  int32_t* label = out.label.data();
  for (int row = 0, cell = 0; cell < cells; ++row) {
    for (const int end = cell + cols; cell < end; ++cell) {
      if (!member[cell]) {
        label[cell] = ClusterLabels::kNone;
        continue;
      }
      const int32_t parent = parents[cell];
      if (parent == cell) {
        label[cell] = static_cast<int32_t>(out.size.size());
        out.size.push_back(0);
        last_row_.push_back(-1);
        rows_spanned_.push_back(0);
      } else {
        label[cell] = label[parent];
      }
      const int32_t id = label[cell];
      ++out.size[id];
      rows_spanned_[id] += last_row_[id] != row;
      last_row_[id] = row;
    }
  }
  out.kept.resize(out.size.size());
  out.kept[0] = 0;
  for (std::size_t id = 1; id < out.size.size(); ++id) {
    out.kept[id] = size_rule_keeps(rule, out.size[id], rows_spanned_[id]);
  }
}

}  // namespace adaptive_lego_loam
