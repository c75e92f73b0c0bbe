#include "adaptive_lego_loam/core/mapping/keyframe_merging.h"

#include <algorithm>
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
  std::vector<double> path_lengths;  // of the group's keyframes
  for (int i = first; i <= last; ++i) {
    if (i > 0)
      path_length_ +=
          (keyframes[i].pose.translation() - keyframes[i - 1].pose.translation()).norm();
    path_lengths.push_back(path_length_);
  }
  const int anchor = (first + last) / 2;
  if (place_is_stored(keyframes, first, path_lengths)) {
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
  anchors_.push_back({anchor, path_lengths[anchor - first]});
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

// Whether each keyframe of the group lies within half the merge radius of a merged keyframe of an
// earlier pass: that keyframe's cloud (its points within the merge radius) then holds what the
// group saw around it. An earlier pass is one at least twice the merge radius away along the path
// driven: anchors of the road just driven are never counted, however close (a slow tight turn).
bool KeyframeMerger::place_is_stored(const std::vector<Keyframe>& keyframes, int first,
                                     const std::vector<double>& path_lengths) const {
  const double cover_radius =
      0.5 * (params_.keyframe_merge_radius > 0.0 ? params_.keyframe_merge_radius
                                                 : params_.local_map_radius);
  const double squared_cover = cover_radius * cover_radius;
  const double earlier_pass_gap = 4.0 * cover_radius;
  for (std::size_t k = 0; k < path_lengths.size(); ++k) {
    const Eigen::Vector3d position = keyframes[first + k].pose.translation();
    const bool covered = std::any_of(anchors_.begin(), anchors_.end(), [&](const Anchor& older) {
      return path_lengths[k] - older.path_length >= earlier_pass_gap &&
             (keyframes[older.keyframe].pose.translation() - position).squaredNorm() <=
                 squared_cover;
    });
    if (!covered) return false;
  }
  return true;
}

}  // namespace adaptive_lego_loam
