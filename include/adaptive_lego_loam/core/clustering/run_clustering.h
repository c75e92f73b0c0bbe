#pragma once
// Scan-line run clustering (Zermas, Izzat, Papanikolopoulos 2017, "Fast segmentation of 3D point
// clouds: a paradigm on LiDAR data for autonomous vehicle applications") on the rows of a range
// image. Each row is cut into runs: consecutive points of the row (in column order, the row
// wrapping around) closer than th_run share a run. Rows are visited from the top; every point
// looks for its nearest point in the row visited before (the row above) and, when that point is
// closer than th_merge, the two runs merge. Merges are kept in a union-find forest, so a run that
// touches two earlier clusters joins them, as the paper's label equivalences do.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/cluster_labels.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

struct RunClusteringParams {
  double run_threshold = 0.5;    // th_run, m: between consecutive points of a row
  double merge_threshold = 1.0;  // th_merge, m: between a point and its nearest point above
  int min_points = 1;            // clusters smaller than this are not kept
};

class RunClustering {
 public:
  RunClustering(const RangeImageGeometry& geometry, const RunClusteringParams& params);
  // Clusters the occupied cells not flagged in `excluded` (may be empty).
  void cluster(const RangeImage& image, const std::vector<uint8_t>& excluded, ClusterLabels& out);

 private:
  // Cuts the row's points (`row_cells_`) into runs, one union-find node each.
  void find_runs(const RangeImage& image);
  // Merges each run of the current row with the runs of the row above that hold the nearest
  // point of its points, when within th_merge.
  void merge_with_row_above(const RangeImage& image);
  // How many columns to each side can hold a point within th_merge of a point at this
  // horizontal range.
  int merge_half_window(float horizontal_range) const;

  RangeImageGeometry geometry_;
  RunClusteringParams params_;
  std::vector<int32_t> parent_;     // union-find over runs
  std::vector<int32_t> run_of_;     // per cell: its run, or -1
  std::vector<int32_t> row_cells_;  // the current row's cells, in column order
  std::vector<int32_t> above_cells_;
};

}  // namespace adaptive_lego_loam
