#include "adaptive_lego_loam/core/mapping/map_assembly.h"

#include <optional>

#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {
namespace {

void add_layer(const Keyframe& keyframe, MapLayer layer, Cloud& out) {
  if (layer != MapLayer::kSurfaces) keyframe.corners->unpack(keyframe.pose, out);
  if (layer != MapLayer::kCorners) keyframe.surfaces->unpack(keyframe.pose, out);
}

}  // namespace

CloudPtr assemble_map(const std::vector<Keyframe>& keyframes, MapLayer layer, double leaf) {
  CloudPtr all(new Cloud);
  std::optional<VoxelSums> sums;
  if (leaf > 0.0) sums.emplace(leaf);
  Cloud placed;
  for (const Keyframe& keyframe : keyframes) {
    if (!keyframe.has_clouds()) continue;
    // Filtered a keyframe at a time: the whole map's points never exist at once.
    placed.clear();
    add_layer(keyframe, layer, sums ? placed : *all);
    if (sums) sums->add(placed);
  }
  return sums ? sums->centroids() : all;
}

}  // namespace adaptive_lego_loam
