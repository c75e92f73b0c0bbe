#pragma once
// docs/METHOD.md, step 5: the scene's skeleton is the set of points that survive in both the large
// Euclidean clusters (large objects) and the depth clusters taken with the strict beta0 (surfaces).

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/cluster_labels.h"
#include "adaptive_lego_loam/core/projection/range_image.h"

namespace adaptive_lego_loam {

// One flag per cell: kept by both labelings. Returns the number of skeleton cells.
int extract_skeleton(const ClusterLabels& euclidean, const ClusterLabels& depth,
                     std::vector<uint8_t>& skeleton);

// The fragments are the points of kept Euclidean clusters that the strict depth clustering broke
// off the skeleton. Of those with both row neighbours, the fraction whose range lies on a smooth
// line along the row, |r(c-1) + r(c+1) - 2 r(c)| < tolerance_m: high for a rail or a wall seen at
// grazing incidence, low for leaves. 0 without any such fragment point.
double fragment_smoothness(const RangeImage& image, const ClusterLabels& euclidean,
                           const std::vector<uint8_t>& skeleton, double tolerance_m);

}  // namespace adaptive_lego_loam
