#pragma once
// A keyframe's place as seen from above, for loop candidates that do not depend on the drift: a
// polar grid around the keyframe (rings out to max_radius, sectors all around) holding the
// highest point of each cell, in the keyframe's levelled frame (z up). Turning the sensor on the
// spot shifts the grid's sectors; the per-ring means (the ring key) do not change, so a search
// over ring keys finds the same place whatever the heading, and the best sector shift between
// two grids gives their relative yaw. (The idea of Kim and Kim's Scan Context.)

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/common/params.h"

namespace adaptive_lego_loam {

class PlaceDescriptor {
 public:
  PlaceDescriptor() = default;
  explicit PlaceDescriptor(const PlaceRecognitionParams& params);

  // Adds points given in the sensor frame; `level` turns that frame into the levelled one (the
  // keyframe's roll and pitch). Call finish() once every cloud is in.
  void add(const Cloud& points, const Eigen::Matrix3f& level);
  void finish();

  bool empty() const { return occupied_ == 0; }
  const std::vector<float>& ring_key() const { return ring_key_; }
  int sectors() const { return sectors_; }
  std::size_t bytes() const {
    return cells_.capacity() +
           (ring_key_.capacity() + sector_key_.capacity() + column_norm_.capacity()) *
               sizeof(float);
  }

  // 1 - the mean cosine similarity of the sector columns occupied in both, at the sector shift
  // that fits best: 0 the same place, 1 nothing alike. `best_shift` (may be null) gets the shift:
  // this grid's sector s matches other's sector s + shift. The shifts compared in full are those
  // around the few best by the sectors' mean heights (the sector key).
  double distance(const PlaceDescriptor& other, int* best_shift = nullptr) const;
  // The yaw of this keyframe relative to `other`'s (rad) for a shift from distance().
  double yaw_of_shift(int shift) const;

 private:
  double distance_at(const PlaceDescriptor& other, int shift) const;

  int rings_ = 0, sectors_ = 0;
  float max_radius_ = 0.f, height_offset_ = 0.f;
  std::vector<uint8_t> cells_;      // sector-major: height above -height_offset in 0.1 m, 0 = empty
  std::vector<float> ring_key_;     // per ring: mean height
  std::vector<float> sector_key_;   // per sector: mean height
  std::vector<float> column_norm_;  // per sector: |cells of the sector|
  int occupied_ = 0;
};

}  // namespace adaptive_lego_loam
