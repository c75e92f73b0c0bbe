#include "adaptive_lego_loam/core/mapping/keyframe_merging.h"

#include <cmath>

namespace adaptive_lego_loam {

KeyframeMerger::KeyframeMerger(const MappingParams& params) : params_(params) {}

int KeyframeMerger::merge_old(std::vector<Keyframe>& keyframes,
                              std::vector<std::pair<int, int>>* revisits) {
  if (params_.keyframe_merge_group <= 1) return 0;
  int merged = 0;
  const int size = static_cast<int>(keyframes.size());
  while (next_ + params_.keyframe_merge_group <= size - params_.keyframe_merge_after) {
    const int last = next_ + params_.keyframe_merge_group - 1;
    if (!merge_group(keyframes, next_, last) && revisits) revisits->emplace_back(next_, last);
    next_ += params_.keyframe_merge_group;
    ++merged;
  }
  return merged;
}

bool KeyframeMerger::merge_group(std::vector<Keyframe>& keyframes, int first, int last) {
  const int anchor = (first + last) / 2;
  if (place_is_stored(keyframes, anchor)) {
    for (int i = first; i <= last; ++i)
      keyframes[i].corners.reset(), keyframes[i].surfaces.reset();
    return false;
  }
  Cloud corners, surfaces;
  const Eigen::Isometry3d to_anchor = keyframes[anchor].pose.inverse();
  for (int i = first; i <= last; ++i) {
    Keyframe& keyframe = keyframes[i];
    if (!keyframe.has_clouds()) continue;
    const Eigen::Isometry3d in_anchor = to_anchor * keyframe.pose;
    keyframe.corners->unpack(in_anchor, corners);
    keyframe.surfaces->unpack(in_anchor, surfaces);
    keyframe.corners.reset();
    keyframe.surfaces.reset();
  }
  keyframes[anchor].corners = pack(within_radius(*filter_(corners, params_.corner_voxel)));
  keyframes[anchor].surfaces = pack(within_radius(*filter_(surfaces, params_.surface_voxel)));
  anchors_.push_back(anchor);
  return true;
}

Cloud KeyframeMerger::within_radius(const Cloud& cloud) const {
  if (params_.keyframe_merge_radius <= 0.0) return cloud;
  const float squared_radius =
      static_cast<float>(params_.keyframe_merge_radius * params_.keyframe_merge_radius);
  Cloud near;
  near.reserve(cloud.size());
  for (const CloudPoint& p : cloud) {
    if (p.getVector3fMap().squaredNorm() <= squared_radius) near.push_back(p);
  }
  return near;
}

// Whether an older merged keyframe lies within half a group's length of this one: its cloud then
// covers this group's ground.
bool KeyframeMerger::place_is_stored(const std::vector<Keyframe>& keyframes, int anchor) const {
  const double reach = 0.5 * params_.keyframe_merge_group * params_.keyframe_distance;
  const Eigen::Vector3d position = keyframes[anchor].pose.translation();
  for (int older : anchors_) {
    if ((keyframes[older].pose.translation() - position).norm() <= reach) return true;
  }
  return false;
}

}  // namespace adaptive_lego_loam
