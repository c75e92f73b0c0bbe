#pragma once
// Voxel filters of the odometry and mapping stages: each voxel of a grid anchored at the origin
// keeps the centroid of its points (PCL's VoxelGrid, up to rounding and the order of the output).

#include "adaptive_lego_loam/core/cloud.h"
#include "adaptive_lego_loam/core/voxel_hash.h"

namespace adaptive_lego_loam {

// Sums of the points falling in each voxel: their centroids are the voxel filter of every point
// added, which may come in several clouds (the loop closure's map, a keyframe at a time).
class VoxelSums {
 public:
  explicit VoxelSums(double leaf) : inverse_leaf_(1.0 / leaf) {}
  void add(const Cloud& points);
  void reserve(std::size_t voxels) { sums_.reserve(voxels); }
  CloudPtr centroids() const;

 private:
  struct Sum {
    int count = 0;
    double x = 0.0, y = 0.0, z = 0.0, intensity = 0.0;
  };
  double inverse_leaf_;
  VoxelHashTable<Sum> sums_;
};

// Voxel-filtered copy of `cloud` (no filtering when leaf <= 0).
CloudPtr voxel_filter(const Cloud& cloud, double leaf);

}  // namespace adaptive_lego_loam
