#pragma once
// docs/METHOD.md, step 5: the scene's skeleton is the set of points that survive in both the large
// Euclidean clusters (large objects) and the depth clusters taken with the strict beta0 (surfaces).

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/clustering/cluster_labels.h"

namespace adaptive_lego_loam {

// One flag per cell: kept by both labelings. Returns the number of skeleton cells.
int extract_skeleton(const ClusterLabels& euclidean, const ClusterLabels& depth,
                     std::vector<uint8_t>& skeleton);

}  // namespace adaptive_lego_loam
