#include "adaptive_lego_loam/core/mapping/map_assembly.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "adaptive_lego_loam/core/spatial/voxel_filter.h"
#include "adaptive_lego_loam/core/spatial/voxel_hash.h"

namespace adaptive_lego_loam {
namespace {

using Tile = std::pair<int64_t, int64_t>;  // x, y

void add_layer(const Keyframe& keyframe, MapLayer layer, Cloud& out) {
  if (layer != MapLayer::kSurfaces) keyframe.corners->unpack(keyframe.pose, out);
  if (layer != MapLayer::kCorners) keyframe.surfaces->unpack(keyframe.pose, out);
}

// Tiles are whole voxels wide, so that a voxel's points all fall in one tile.
class Tiling {
 public:
  explicit Tiling(double leaf)
      : inverse_leaf_(1.0 / leaf),
        voxels_per_tile_(std::max<int64_t>(1, std::llround(kMapTileMetres / leaf))) {}
  Tile of(const CloudPoint& p) const { return {cell(p.x), cell(p.y)}; }

 private:
  int64_t cell(float coordinate) const {
    const int64_t voxel = voxel_index(coordinate, inverse_leaf_);
    const int64_t tile = voxel / voxels_per_tile_;
    return tile * voxels_per_tile_ > voxel ? tile - 1 : tile;  // floor
  }
  double inverse_leaf_;
  int64_t voxels_per_tile_;
};

// The keyframes whose points reach each tile, in keyframe order.
std::map<Tile, std::vector<int>> keyframes_by_tile(const std::vector<Keyframe>& keyframes,
                                                   MapLayer layer, const Tiling& tiling) {
  std::map<Tile, std::vector<int>> by_tile;
  Cloud placed;
  for (int i = 0; i < static_cast<int>(keyframes.size()); ++i) {
    if (!keyframes[i].has_clouds()) continue;
    placed.clear();
    add_layer(keyframes[i], layer, placed);
    std::vector<Tile> tiles;
    for (const CloudPoint& p : placed)
      tiles.push_back(tiling.of(p));
    std::sort(tiles.begin(), tiles.end());
    tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
    for (const Tile& tile : tiles)
      by_tile[tile].push_back(i);
  }
  return by_tile;
}

}  // namespace

CloudPtr assemble_map(const std::vector<Keyframe>& keyframes, MapLayer layer, double leaf) {
  CloudPtr map(new Cloud);
  if (leaf <= 0.0) {
    for (const Keyframe& keyframe : keyframes) {
      if (keyframe.has_clouds()) add_layer(keyframe, layer, *map);
    }
    return map;
  }
  // A tile at a time, each keyframe unpacked for every tile it reaches: the voxel sums of the
  // whole map (100 bytes or more a voxel, half as much again while their table grows) never exist
  // at once.
  const Tiling tiling(leaf);
  VoxelSums sums(leaf);
  Cloud placed, in_tile;
  for (const auto& [tile, indices] : keyframes_by_tile(keyframes, layer, tiling)) {
    sums.reset(leaf);
    for (int i : indices) {
      placed.clear();
      add_layer(keyframes[i], layer, placed);
      in_tile.clear();
      for (const CloudPoint& p : placed) {
        if (tiling.of(p) == tile) in_tile.push_back(p);
      }
      sums.add(in_tile);
    }
    *map += *sums.centroids();
  }
  return map;
}

}  // namespace adaptive_lego_loam
