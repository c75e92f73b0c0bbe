#pragma once
// Scan-to-map matching (LeGO-LOAM's mapOptimization) with Ceres: the scan's edges against lines
// and its surfaces against planes fitted to the five nearest points of a local map built from
// the surrounding keyframes. Degenerate directions of the normal equations (LOAM's eigenvalue
// test) receive no update.

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/cloud.h"
#include "adaptive_lego_loam/core/keyframe.h"
#include "adaptive_lego_loam/core/params.h"
#include "adaptive_lego_loam/core/voxel_map.h"

namespace adaptive_lego_loam {

// The local map: the chosen keyframes' features in the map frame, voxel-filtered.
class LocalMap {
 public:
  explicit LocalMap(const MappingParams& params);
  // Updates from the keyframes near `position` when that set (or `version`, bumped when
  // keyframe poses change) differs from the last update: keyframes that left the set are taken
  // out, new ones put in (everything again after a version change). Returns whether it changed.
  bool update(const std::vector<Keyframe>& keyframes, const Eigen::Vector3d& position, int version);
  const VoxelMap& corner_map() const { return corner_map_; }
  const VoxelMap& surface_map() const { return surface_map_; }
  // The voxel centroids, made on each call (for display).
  CloudPtr corners() const { return corner_map_.centroids(); }
  CloudPtr surfaces() const { return surface_map_.centroids(); }
  bool empty() const { return corner_map_.empty() && surface_map_.empty(); }

 private:
  // A keyframe's features as they were put in the map (to take them out again).
  struct Placed {
    CloudPtr corners, surfaces;
  };
  std::vector<int> select(const std::vector<Keyframe>& keyframes,
                          const Eigen::Vector3d& position) const;
  void put_in(const Keyframe& keyframe);
  void take_out(int keyframe);

  MappingParams params_;
  std::vector<int> selected_;
  int version_ = -1;
  VoxelMap corner_map_, surface_map_;
  std::map<int, Placed> placed_;
};

struct MapMatchResult {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  int edge_matches = 0;
  int plane_matches = 0;
  int iterations = 0;
  int degenerate_directions = 0;     // of the 6, held at the guess
  double smallest_eigenvalue = 0.0;  // of the normal equations at the first iteration
  bool matched = false;              // false with too few correspondences: pose = guess
};

// A soft constraint along the direction the scan constrains least (the ambient filter's weak
// direction, sensor frame), pulling the translation toward the prediction.
struct WeakDirectionPrior {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  double weight = 0.0;
};

class ScanToMapMatcher {
 public:
  explicit ScanToMapMatcher(const MappingParams& params);
  // `corners` and `surfaces` in the sensor frame; `guess` the sensor pose in the map.
  MapMatchResult match(const Cloud& corners, const Cloud& surfaces, const LocalMap& map,
                       const Eigen::Isometry3d& guess,
                       const std::optional<WeakDirectionPrior>& prior = std::nullopt) const;

 private:
  MappingParams params_;
};

}  // namespace adaptive_lego_loam
