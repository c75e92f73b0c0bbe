#pragma once
// The local map of the mapping stage: the features of the keyframes around the sensor, in the map
// frame, in voxel maps that keyframes enter and leave one at a time.

#include <Eigen/Geometry>
#include <map>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"
#include "adaptive_lego_loam/core/spatial/voxel_map.h"

namespace adaptive_lego_loam {

// The local map: the chosen keyframes' features in the map frame, voxel-filtered.
class LocalMap {
 public:
  // The largest search radius of its queries (m): a little beyond LOAM's 1 m, so that a point
  // rejected at 1 m need not be searched again at once.
  static constexpr float kSearchRadius = 1.1f;

  explicit LocalMap(const MappingParams& params);
  // Follows the keyframes near `position`: keyframes that left the chosen set are taken out, new
  // ones put in. Returns whether the map changed.
  bool update(const std::vector<Keyframe>& keyframes, const Eigen::Vector3d& position);
  // Puts a keyframe in whatever its position, for a map of chosen keyframes (a loop candidate's
  // neighbourhood); not to be mixed with update().
  void add(const Keyframe& keyframe) { active_.put_in(keyframe); }
  // Keyframe poses changed (a loop closed); `correction` takes the old map frame to the new one
  // near the current position (the newest keyframe's change: new pose = correction * old). The
  // keyframes are placed again from their new poses over the next updates, a few at a time, and
  // until then queries go to the old placement through to_placement().
  void keyframes_moved(const Eigen::Isometry3d& correction);
  // Keyframes [first, first + count) left the keyframe list and the later ones moved down by
  // `count` (localization lets its drive's old keyframes go): those removed leave the map, the
  // others keep their places under their new indices.
  void keyframes_removed(int first, int count);
  // From the map frame to the frame the map's points are in (identity but while placing again).
  const Eigen::Isometry3d& to_placement() const { return to_placement_; }

  const VoxelMap& corner_map() const { return active_.corners; }
  const VoxelMap& surface_map() const { return active_.surfaces; }
  // The voxel centroids in the frame of to_placement(), made on each call (for display). By
  // value: a range-for over a temporary pointer's cloud would dangle.
  Cloud corners() const { return active_.corners.centroids(); }
  Cloud surfaces() const { return active_.surfaces.centroids(); }
  bool empty() const { return active_.corners.empty() && active_.surfaces.empty(); }

 private:
  // A keyframe's packed features and the pose they were placed by: unpacked again, they give the
  // points put in exactly, to take them out (its keyframe may have moved or merged since).
  struct Placed {
    PackedCloudPtr corners, surfaces;
    Eigen::Isometry3d pose;
  };
  // Keyframes placed in voxel maps.
  struct Placement {
    Placement(const MappingParams& params);
    void put_in(const Keyframe& keyframe);
    void take_out(int keyframe);
    bool holds(int keyframe) const { return placed.count(keyframe) > 0; }
    void clear();
    void keyframes_removed(int first, int count);

    VoxelMap corners, surfaces;
    std::map<int, Placed> placed;
  };
  std::vector<int> select(const std::vector<Keyframe>& keyframes,
                          const Eigen::Vector3d& position) const;
  // Makes `placement` hold exactly `chosen`, putting in at most `most_new` keyframes; returns
  // whether it then holds them all.
  static bool follow(Placement& placement, const std::vector<Keyframe>& keyframes,
                     const std::vector<int>& chosen, int most_new, bool* changed);

  MappingParams params_;
  Placement active_, replacement_;
  bool replacing_ = false;
  Eigen::Isometry3d to_placement_ = Eigen::Isometry3d::Identity();
};

}  // namespace adaptive_lego_loam
