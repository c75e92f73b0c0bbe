#pragma once
// Voxel filters of the odometry and mapping stages: each voxel of a grid anchored at the origin
// keeps the centroid of its points (PCL's VoxelGrid, up to rounding and the order of the output).

#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/cloud.h"

namespace adaptive_lego_loam {

// Sums of the points falling in each voxel: their centroids are the voxel filter of every point
// added and not removed since, without filtering them all again when a few change (the local
// map). An open-addressing table: one probe per point and a linear walk for the centroids.
class VoxelSums {
 public:
  explicit VoxelSums(double leaf) : inverse_leaf_(1.0 / leaf) {}
  void add(const Cloud& points) { accumulate(points, 1); }
  // `points` must have been added before, unchanged.
  void remove(const Cloud& points) { accumulate(points, -1); }
  void clear();
  CloudPtr centroids() const;

 private:
  struct Slot {
    uint64_t key = kEmpty;
    int count = 0;
    double x = 0.0, y = 0.0, z = 0.0, intensity = 0.0;
  };
  static constexpr uint64_t kEmpty = ~uint64_t{0};

  void accumulate(const Cloud& points, int sign);
  uint64_t key_of(const CloudPoint& p) const;
  std::size_t home(uint64_t key) const;
  Slot& find_or_insert(uint64_t key);
  void erase(std::size_t slot);
  void grow();

  double inverse_leaf_;
  std::vector<Slot> slots_;  // a power of two of them, at most half used
  std::size_t used_ = 0;
  int shift_ = 64;  // home slot: the top log2(slots) bits of the hash
};

// Voxel-filtered copy of `cloud` (no filtering when leaf <= 0).
CloudPtr voxel_filter(const Cloud& cloud, double leaf);

}  // namespace adaptive_lego_loam
