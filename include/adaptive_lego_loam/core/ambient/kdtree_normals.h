#pragma once
// The paper's comparison for step 6 (its Fig. 8): the same weighted normals computed for every
// non-ground point from a KD-tree radius search instead of the skeleton's range-image windows.

#include <vector>

#include "adaptive_lego_loam/core/ambient/skeleton_normals.h"
#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

struct KdTreeNormalParams {
  double radius = 1.0;  // m
  int min_neighbors = 5;
  double max_range = 100.0;  // d_max of the weight
};

// The filter's settings for it: the skeleton normals' depth_0 as the radius, t_0, d_max.
KdTreeNormalParams kdtree_normal_params(const Config& config);

// Every occupied, non-ground cell's point of a segmentation result.
std::vector<ScanPoint> non_ground_points(const SegmentationResult& segmentation);

// One normal per point of `points` with at least min_neighbors within `radius` (PCL KD-tree).
void kdtree_normals(const std::vector<ScanPoint>& points, const KdTreeNormalParams& params,
                    std::vector<NormalFeature>& normals);

}  // namespace adaptive_lego_loam
