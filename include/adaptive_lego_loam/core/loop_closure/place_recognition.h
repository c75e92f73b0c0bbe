#pragma once
// The places of the keyframes (place_descriptor.h), and the loop candidate they give a new
// keyframe whatever the drift: among the places older than min_time_gap, the nearest ring keys
// are compared in full; the best within max_distance, and clearly better than any match
// elsewhere (max_ratio), is the candidate, its guess the matched keyframe's position turned by
// the descriptors' relative yaw. Every keyframe keeps its place,
// merged or not (a descriptor tells a place apart only within a few metres, where merged
// keyframes hold clouds every ten); those of a place driven again are forgotten.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/loop_closure/loop_detection.h"
#include "adaptive_lego_loam/core/loop_closure/place_descriptor.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"

namespace adaptive_lego_loam {

// The keyframe's roll and pitch: turns its sensor frame into the levelled one (z up, same yaw).
Eigen::Matrix3f levelling(const Eigen::Isometry3d& pose);

class PlaceRecognition {
 public:
  explicit PlaceRecognition(const LoopClosureParams& params);

  // The place of a keyframe at `pose` from its points (sensor frame).
  PlaceDescriptor describe(const std::vector<const Cloud*>& clouds,
                           const Eigen::Isometry3d& pose) const;
  void add(int keyframe, double stamp, PlaceDescriptor descriptor);
  // Forgets the places of keyframes first ... last.
  void forget(int first, int last);

  // The candidate for keyframes[current] (whose place was added last), if any.
  std::optional<LoopCandidate> candidate(const std::vector<Keyframe>& keyframes, int current) const;

  std::size_t size() const { return places_.size(); }
  std::size_t bytes() const;

 private:
  LoopClosureParams params_;
  // The places by keyframe index, one entry each in every array. The ring keys lie back to back
  // (params_.place.rings each): every new keyframe reads all of them.
  std::vector<PlaceDescriptor> places_;
  std::vector<int> keyframes_;
  std::vector<double> stamps_;
  std::vector<float> ring_keys_;
};

}  // namespace adaptive_lego_loam
