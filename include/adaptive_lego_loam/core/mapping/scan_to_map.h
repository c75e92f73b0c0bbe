#pragma once
// Scan-to-map matching (LeGO-LOAM's mapOptimization) with Ceres: the scan's edges against lines
// and its surfaces against planes fitted to the five nearest points of the local map. Degenerate
// directions of the normal equations (LOAM's eigenvalue test) receive no update.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/cloud.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/mapping/local_map.h"

namespace adaptive_lego_loam {

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

// One match an iteration (a correspondence search and a solve) at a time, for work spread over
// scans: iterated until done, it gives ScanToMapMatcher::match's result bit for bit. The clouds
// and the map are referenced, not copied: they must outlive it.
class SteppedMapMatch {
 public:
  SteppedMapMatch(const MappingParams& params, const Cloud& corners, const Cloud& surfaces,
                  const LocalMap& map, const Eigen::Isometry3d& guess,
                  const std::optional<WeakDirectionPrior>& prior = std::nullopt,
                  const std::vector<Eigen::Vector3d>& wall_normals = {});
  ~SteppedMapMatch();
  SteppedMapMatch(const SteppedMapMatch&) = delete;
  SteppedMapMatch& operator=(const SteppedMapMatch&) = delete;

  // Converged, out of iterations or of correspondences (an empty map: done at once).
  bool done() const;
  // One iteration; nothing once done.
  void iterate();
  // So far: the pose after the last iteration, the guess before any.
  MapMatchResult result() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

class ScanToMapMatcher {
 public:
  explicit ScanToMapMatcher(const MappingParams& params);
  // `corners` and `surfaces` in the sensor frame; `guess` the sensor pose in the map.
  // `wall_normals` (sensor frame, from wall_normals()) feed the vertical-structure prior when
  // params.vertical_prior_weight > 0.
  MapMatchResult match(const Cloud& corners, const Cloud& surfaces, const LocalMap& map,
                       const Eigen::Isometry3d& guess,
                       const std::optional<WeakDirectionPrior>& prior = std::nullopt,
                       const std::vector<Eigen::Vector3d>& wall_normals = {}) const;

 private:
  MappingParams params_;
};

}  // namespace adaptive_lego_loam
