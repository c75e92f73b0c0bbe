#pragma once
// LeGO-LOAM's feature extraction on the segmented cloud: smoothness over the row neighbours,
// occluded and near-parallel points rejected, each row split into sectors, sharp/less-sharp edges
// and flat/less-flat surfaces picked per sector, ground points only as surfaces.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {

// Feature clouds in the sensor frame; each point's intensity holds its range-image row.
struct FeatureSet {
  CloudPtr sharp{new Cloud};
  CloudPtr less_sharp{new Cloud};  // includes the sharp ones
  CloudPtr flat{new Cloud};
  CloudPtr less_flat{new Cloud};  // includes the flat ones, voxel-filtered per row
  CloudPtr outliers{new Cloud};   // LeGO-LOAM's outlier cloud: dropped clusters, for mapping
  // Replaces every cloud by a new empty one (holders of the old ones keep them intact).
  void clear();
};

// Which points of a segmented cloud become features, in the order they are taken. The choice
// depends on the ranges alone, not on the points' de-skewed positions: it can be made while the
// previous scan is still being registered.
struct FeatureSelection {
  struct Pick {
    int32_t index;  // in the segmented cloud
    int32_t row;
  };
  std::vector<Pick> sharp, less_sharp, flat;
  // Each picked row's less-flat points, voxel-filtered row by row: the picks of row group k are
  // less_flat[group_ends[k - 1] .. group_ends[k]).
  std::vector<Pick> less_flat;
  std::vector<std::size_t> group_ends;
  double ms = 0.0;  // what choosing took (stage "features")
};

class FeatureExtractor {
 public:
  explicit FeatureExtractor(const FeatureParams& params);
  // `points` and `outliers` are the segmented cloud's points and outliers, possibly de-skewed,
  // in its order. The same as select() then assemble().
  void extract(const SegmentedCloud& cloud, const std::vector<ScanPoint>& points,
               const std::vector<ScanPoint>& outliers, FeatureSet& out);
  void select(const SegmentedCloud& cloud, FeatureSelection& out);
  // The clouds of a selection from the points (voxel-filtering the less-flat ones row by row).
  void assemble(const FeatureSelection& selection, const std::vector<ScanPoint>& points,
                const std::vector<ScanPoint>& outliers, FeatureSet& out);

 private:
  void compute_curvature(const SegmentedCloud& cloud);
  void mark_unreliable(const SegmentedCloud& cloud);
  void pick_row(const SegmentedCloud& cloud, int row, FeatureSelection& out);
  void block_neighbours(const SegmentedCloud& cloud, int index);

  FeatureParams params_;
  struct Smoothness {
    float value;
    int32_t index;
  };
  // Of a sector, the points that may become edges (off the ground, curvature above the edge
  // threshold) and those that may become flats (ground, below the surface threshold): only they
  // are sorted.
  std::vector<Smoothness> edge_candidates_, flat_candidates_;
  std::vector<float> curvature_;
  std::vector<uint8_t> picked_;  // no longer available for selection
  std::vector<int8_t> label_;    // 2 sharp, 1 less sharp, -1 flat, 0 none
  FeatureSelection selection_;   // extract()'s
  Cloud row_less_flat_;
  std::size_t less_flat_capacity_ = 0;  // reserved for the next scan
  VoxelFilter voxel_filter_;
};

}  // namespace adaptive_lego_loam
