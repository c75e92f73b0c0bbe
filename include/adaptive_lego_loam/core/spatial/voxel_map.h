#pragma once
// The mapping stage's local map as an incremental voxel filter that answers nearest-neighbour
// queries itself: points go in and out keyframe by keyframe, each voxel keeps the centroid of its
// points, and a query scans the 3 x 3 x 3 coarse cells (each at least the search radius wide)
// around its own, skipping those farther than its k-th best. No KD-tree is rebuilt when keyframes
// enter or leave the map, which is what made the scans that refreshed the map several times slower
// than the others.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/spatial/voxel_hash.h"

namespace adaptive_lego_loam {

class VoxelMap {
 public:
  // `leaf`: the voxel filter's leaf (m); `max_radius`: the largest search radius (m) queries use.
  VoxelMap(double leaf, double max_radius);
  // Moves only: the cell table points into the cells' own storage.
  VoxelMap(const VoxelMap&) = delete;
  VoxelMap& operator=(const VoxelMap&) = delete;
  VoxelMap(VoxelMap&&) = default;
  VoxelMap& operator=(VoxelMap&&) = default;

  void add(const Cloud& points);
  // `points` must have been added before, unchanged.
  void remove(const Cloud& points);
  void clear();  // keeps the memory
  // Room for this many voxels without growing its tables on the way.
  void reserve(std::size_t voxels);
  std::size_t size() const { return voxel_index_.size(); }
  bool empty() const { return size() == 0; }

  // Up to k voxel centroids nearest to `query` within sqrt(max_squared_distance) (inclusive, and
  // never beyond max_radius), nearest first: fills `points` and `squared_distances` (each at
  // least k long) and returns how many it found. Ties go to the centroid met first.
  int nearest(const Eigen::Vector3f& query, int k, Eigen::Vector3f* points,
              float* squared_distances, float max_squared_distance) const;

  // Every voxel's centroid (intensity averaged too), for display.
  Cloud centroids() const;

 private:
  // A voxel's sums, in one array whose freed entries are reused; the hash table maps a voxel's key
  // to its index there (16 bytes a slot: the table is kept at most half full, so its slots
  // outweigh everything else), its cell keeps its centroid, where queries scan it.
  struct Voxel {
    double sum[4] = {0.0, 0.0, 0.0, 0.0};  // x, y, z, intensity
    int count = 0;
    uint32_t cell = 0;
    uint32_t slot = 0;  // in the cell's centroids
  };
  struct Cell {
    uint64_t key = 0;
    std::vector<Eigen::Vector3f> centroids;
    std::vector<uint32_t> voxels;  // of the same slots, in voxels_
  };

  // `visit(point, key)` for every point, the hash slot of a later point already on its way from
  // memory.
  template <class Visit>
  void for_each_key(const Cloud& points, Visit&& visit);
  void add_point(const CloudPoint& p, uint64_t key);
  void remove_point(const CloudPoint& p, uint64_t key);
  uint32_t attach(uint64_t key);
  void detach(uint32_t voxel);
  int64_t cell_of(int64_t voxel_index) const;

  double inverse_leaf_;
  int64_t voxels_per_cell_;  // along each axis
  double cell_size_;
  float cell_size_f_;
  float max_squared_radius_;
  VoxelHashTable<uint32_t> voxel_index_;  // by voxel key
  std::vector<Voxel> voxels_;
  std::vector<uint32_t> free_voxels_;
  // What a query needs of a cell, in the table it looks the cell up in: one memory access less
  // than going through cells_.
  struct CellRef {
    uint32_t index_plus_one = 0;  // in cells_
    uint32_t count = 0;
    const Eigen::Vector3f* centroids = nullptr;  // cells_[index].centroids.data()
  };
  VoxelHashTable<CellRef> cell_refs_;  // by cell key
  std::vector<Cell> cells_;
  std::vector<uint32_t> free_cells_;
};

}  // namespace adaptive_lego_loam
