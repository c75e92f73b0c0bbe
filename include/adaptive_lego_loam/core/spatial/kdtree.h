#pragma once
// Exact k-nearest-neighbour search over a cloud's points, for the few nearest points LOAM's
// correspondences need. A KD-tree over a packed copy of the points, stored in tree order: it
// builds in a fraction of nanoflann's time over PCL points (the odometry builds two trees every
// scan) and answers faster, its leaves being contiguous.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>

#include "adaptive_lego_loam/core/common/cloud.h"

namespace adaptive_lego_loam {

class PointKdTree {
 public:
  PointKdTree();
  ~PointKdTree();
  PointKdTree(PointKdTree&&) noexcept;
  PointKdTree& operator=(PointKdTree&&) noexcept;

  // Indexes `cloud`, which the tree keeps alive.
  void build(CloudConstPtr cloud);
  // Up to k nearest points to `query` within sqrt(max_squared_distance) (inclusive), nearest
  // first: fills `indices` (into the cloud) and `squared_distances` (each at least k long) and
  // returns how many it found. A bound prunes the search: far queries end early.
  int nearest(const Eigen::Vector3f& query, int k, uint32_t* indices, float* squared_distances,
              float max_squared_distance = std::numeric_limits<float>::infinity()) const;
  bool empty() const;
  const Cloud& cloud() const { return *cloud_; }

 private:
  struct Index;
  CloudConstPtr cloud_;
  std::unique_ptr<Index> index_;
};

}  // namespace adaptive_lego_loam
