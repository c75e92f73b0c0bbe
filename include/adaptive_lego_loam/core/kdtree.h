#pragma once
// Exact k-nearest-neighbour search over a cloud's points (nanoflann behind the scenes: two to
// three times faster than PCL's FLANN wrapper for the small k of LOAM's correspondences).

#include <Eigen/Core>
#include <cstdint>
#include <memory>

#include "adaptive_lego_loam/core/cloud.h"

namespace adaptive_lego_loam {

class PointKdTree {
 public:
  PointKdTree();
  ~PointKdTree();
  PointKdTree(PointKdTree&&) noexcept;
  PointKdTree& operator=(PointKdTree&&) noexcept;

  // Indexes `cloud`, which the tree keeps alive.
  void build(CloudConstPtr cloud);
  // Up to k nearest points to `query`, nearest first: fills `indices` and `squared_distances`
  // (each at least k long) and returns how many it found.
  int nearest(const Eigen::Vector3f& query, int k, uint32_t* indices,
              float* squared_distances) const;
  bool empty() const;
  const Cloud& cloud() const { return *cloud_; }

 private:
  struct Index;
  CloudConstPtr cloud_;
  std::unique_ptr<Index> index_;
};

}  // namespace adaptive_lego_loam
