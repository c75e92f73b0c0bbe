#pragma once
// Bounded memory for long runs: keyframes that have left the recent window are merged a group at
// a time. The group's clouds join its middle keyframe's (in that keyframe's frame, voxel-filtered:
// consecutive keyframes see mostly the same points), and the others keep their pose only. A group
// whose keyframes all lie near merged keyframes of an earlier pass (a place driven again) keeps no
// cloud at all. Local map, loop closure and saved maps use the keyframes that hold clouds; every
// keyframe stays a node of the pose graph.

#include <utility>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {

class KeyframeMerger {
 public:
  explicit KeyframeMerger(const MappingParams& params);
  // Merges every group that is old enough now; returns how many groups it merged. `revisits`
  // (may be null) gets the groups found already stored, as [first, last] keyframe indices.
  int merge_old(std::vector<Keyframe>& keyframes,
                std::vector<std::pair<int, int>>* revisits = nullptr);
  // Keyframes before this index are merged.
  int merged_until() const { return next_; }

 private:
  // Returns false when the group's place was already stored (the group keeps no cloud).
  bool merge_group(std::vector<Keyframe>& keyframes, int first, int last);
  // `path_lengths`: m driven from the first keyframe to each of the group's, from `first` on.
  bool place_is_stored(const std::vector<Keyframe>& keyframes, int first,
                       const std::vector<double>& path_lengths) const;
  // The points of `cloud` (anchor frame) within keyframe_merge_radius.
  Cloud within_radius(const Cloud& cloud) const;

  MappingParams params_;
  int next_ = 0;
  struct Anchor {
    int keyframe;        // a merged keyframe that kept a cloud
    double path_length;  // m driven from the first keyframe to it
  };
  std::vector<Anchor> anchors_;
  double path_length_ = 0.0;  // m driven from the first keyframe to the last merged one
  VoxelFilter filter_;
};

}  // namespace adaptive_lego_loam
