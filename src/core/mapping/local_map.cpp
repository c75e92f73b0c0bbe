#include "adaptive_lego_loam/core/mapping/local_map.h"

#include <algorithm>

#include "adaptive_lego_loam/core/common/workers.h"

namespace adaptive_lego_loam {

LocalMap::Placement::Placement(const MappingParams& params)
    : corners(params.corner_voxel, kSearchRadius), surfaces(params.surface_voxel, kSearchRadius) {}

void LocalMap::Placement::put_in(const Keyframe& keyframe) {
  run_both([&] { corners.add(*keyframe.corners->unpack(keyframe.pose)); },
           [&] { surfaces.add(*keyframe.surfaces->unpack(keyframe.pose)); });
  placed[keyframe.index] = {keyframe.corners, keyframe.surfaces, keyframe.pose};
}

void LocalMap::Placement::take_out(int keyframe) {
  const auto found = placed.find(keyframe);
  const Placed& features = found->second;
  run_both([&] { corners.remove(*features.corners->unpack(features.pose)); },
           [&] { surfaces.remove(*features.surfaces->unpack(features.pose)); });
  placed.erase(found);
}

void LocalMap::Placement::keyframes_removed(int first, int count) {
  for (int index = first; index < first + count; ++index) {
    if (holds(index)) take_out(index);
  }
  // In increasing order: each moves below every key not yet moved, so none is overwritten.
  for (auto it = placed.lower_bound(first + count); it != placed.end();) {
    placed.emplace(it->first - count, std::move(it->second));
    it = placed.erase(it);
  }
}

void LocalMap::Placement::clear() {
  corners.clear();
  surfaces.clear();
  placed.clear();
}

LocalMap::LocalMap(const MappingParams& params)
    : params_(params), active_(params), replacement_(params) {
  // About a VLP-16 local map (HDL-64E's grows once more): growing a table re-inserts every voxel
  // in one scan.
  active_.corners.reserve(1 << 15);
  active_.surfaces.reserve(1 << 16);
}

std::vector<int> LocalMap::select(const std::vector<Keyframe>& keyframes,
                                  const Eigen::Vector3d& position) const {
  std::vector<int> chosen;
  const double radius_squared = params_.local_map_radius * params_.local_map_radius;
  // The newest keyframes stay out while older ones exist (see
  // MappingParams::local_map_lag_keyframes).
  const int newest = static_cast<int>(keyframes.size()) - 1;
  for (int i = newest - std::min(params_.local_map_lag_keyframes, newest); i >= 0; --i) {
    if (!keyframes[i].has_clouds()) continue;
    if ((keyframes[i].pose.translation() - position).squaredNorm() > radius_squared) continue;
    chosen.push_back(i);
    if (static_cast<int>(chosen.size()) >= params_.local_map_keyframes) break;
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

bool LocalMap::follow(Placement& placement, const std::vector<Keyframe>& keyframes,
                      const std::vector<int>& chosen, int most_new, bool* changed) {
  std::vector<int> leaving;
  for (const auto& entry : placement.placed) {
    if (!std::binary_search(chosen.begin(), chosen.end(), entry.first))
      leaving.push_back(entry.first);
  }
  for (int index : leaving)
    placement.take_out(index);
  bool complete = true;
  int added = 0;
  for (int index : chosen) {
    if (placement.holds(index)) continue;
    if (added == most_new) {
      complete = false;
      break;
    }
    placement.put_in(keyframes[index]);
    ++added;
  }
  *changed = !leaving.empty() || added > 0;
  return complete;
}

bool LocalMap::update(const std::vector<Keyframe>& keyframes, const Eigen::Vector3d& position) {
  const std::vector<int> chosen = select(keyframes, position);
  bool changed = false;
  if (!replacing_) {
    follow(active_, keyframes, chosen, static_cast<int>(chosen.size()), &changed);
    return changed;
  }
  // Placing every keyframe again at once would cost one scan tens of milliseconds.
  constexpr int kReplacedPerUpdate = 2;
  if (!follow(replacement_, keyframes, chosen, kReplacedPerUpdate, &changed)) return false;
  std::swap(active_, replacement_);
  // The old placement's memory goes back: a second placement exists only while placing again.
  replacement_ = Placement(params_);
  replacing_ = false;
  to_placement_ = Eigen::Isometry3d::Identity();
  return true;
}

void LocalMap::keyframes_removed(int first, int count) {
  active_.keyframes_removed(first, count);
  replacement_.keyframes_removed(first, count);
}

void LocalMap::keyframes_moved(const Eigen::Isometry3d& correction) {
  if (active_.placed.empty()) return;  // nothing placed with the old poses
  to_placement_ = to_placement_ * correction.inverse();
  replacement_ = Placement(params_);
  // Room for what the active placement holds: growing a table re-inserts all it holds at once.
  replacement_.corners.reserve(active_.corners.size());
  replacement_.surfaces.reserve(active_.surfaces.size());
  replacing_ = true;
}

}  // namespace adaptive_lego_loam
