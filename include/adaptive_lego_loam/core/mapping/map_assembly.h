#pragma once
// The map as one cloud: every keyframe's features placed by its pose, for saving and display.

#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"

namespace adaptive_lego_loam {

enum class MapLayer { kCorners, kSurfaces, kAll };

// The map is filtered in square tiles of about this size (m) in x and y, one at a time.
constexpr double kMapTileMetres = 100.0;

// The keyframes' clouds of `layer` in the map frame, voxel-filtered with `leaf` (<= 0: every
// point), tile by tile (the centroids of one tile, then the next). Keyframes without clouds
// (merged into another) add nothing.
CloudPtr assemble_map(const std::vector<Keyframe>& keyframes, MapLayer layer, double leaf);

}  // namespace adaptive_lego_loam
