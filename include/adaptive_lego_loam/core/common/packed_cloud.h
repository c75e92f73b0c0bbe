#pragma once
// A cloud stored in 8 bytes a point, for the keyframes a long run keeps: 16-bit coordinates on a
// grid fine enough for the cloud's extent (a 120 m scan rounds by at most 2 mm) and a 16-bit
// intensity (1/256 steps in [-128, 128): keyframe intensities hold range-image rows).

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"

namespace adaptive_lego_loam {

class PackedCloud {
 public:
  PackedCloud() = default;
  explicit PackedCloud(const Cloud& cloud);

  std::size_t size() const { return points_.size(); }
  bool empty() const { return points_.empty(); }
  // The grid step (m): a coordinate is off by at most half of it.
  float step() const { return step_; }
  std::size_t bytes() const { return points_.capacity() * sizeof(Point); }

  // Appends the points, moved by `pose`, to `out`.
  void unpack(const Eigen::Isometry3d& pose, Cloud& out) const;
  CloudPtr unpack(const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) const;

 private:
  struct Point {
    int16_t x, y, z, intensity;
  };
  std::vector<Point> points_;
  float step_ = 0.f;
};

using PackedCloudPtr = std::shared_ptr<const PackedCloud>;

inline PackedCloudPtr pack(const Cloud& cloud) {
  return std::make_shared<const PackedCloud>(cloud);
}

}  // namespace adaptive_lego_loam
