#pragma once
// Voxel filters of the odometry and mapping stages: each voxel of a grid anchored at the origin
// keeps the centroid of its points (PCL's VoxelGrid, up to rounding and the order of the output).

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/spatial/voxel_hash.h"

namespace adaptive_lego_loam {

// Sums of the points falling in each voxel: their centroids are the voxel filter of every point
// added, which may come in several clouds (the loop closure's map, a keyframe at a time).
class VoxelSums {
 public:
  explicit VoxelSums(double leaf = 1.0) : inverse_leaf_(1.0 / leaf) {}
  void add(const Cloud& points);
  void reserve(std::size_t voxels) { sums_.reserve(voxels); }
  // Forgets every voxel (keeping the memory) and takes a new leaf.
  void reset(double leaf);
  // Every voxel's centroid, in the table's order (which depends on the table's size: a filter
  // used again gives the same cloud in another order).
  CloudPtr centroids() const;

 private:
  struct Sum {
    int count = 0;
    double x = 0.0, y = 0.0, z = 0.0, intensity = 0.0;
  };
  double inverse_leaf_;
  VoxelHashTable<Sum> sums_;
};

// A voxel filter that keeps its table from one cloud to the next: the stages that filter every
// scan hold one, and do not allocate and grow a table each time.
class VoxelFilter {
 public:
  // Voxel-filtered copy of `cloud` (no filtering when leaf <= 0).
  CloudPtr operator()(const Cloud& cloud, double leaf);
  // The same of both clouds together, without joining them first.
  CloudPtr operator()(const Cloud& cloud, const Cloud& more, double leaf);

 private:
  VoxelSums sums_;
};

// A one-off voxel filter.
CloudPtr voxel_filter(const Cloud& cloud, double leaf);

}  // namespace adaptive_lego_loam
