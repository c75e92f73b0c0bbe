#pragma once
// DBSCAN (Ester et al. 1996) over unordered points, with KD-tree radius queries. A point is a
// core point when at least min_samples points (itself included) lie within eps of it; clusters
// are the core points linked by eps-neighbourhoods plus the non-core points within eps of one of
// them (border points, given to the first cluster that reaches them); the rest is noise.

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"

namespace adaptive_lego_loam {

struct DbscanParams {
  double eps = 0.75;    // m
  int min_samples = 5;  // including the point itself
};

constexpr int32_t kDbscanNoise = -1;

// Per point: its cluster id (0, 1, ... in the order clusters are found) or kDbscanNoise.
// Non-finite points are noise.
std::vector<int32_t> dbscan(const std::vector<ScanPoint>& points, const DbscanParams& params);

}  // namespace adaptive_lego_loam
