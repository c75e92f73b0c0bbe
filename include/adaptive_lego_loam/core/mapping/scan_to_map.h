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
#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"
#include "adaptive_lego_loam/core/odometry/observability.h"

namespace adaptive_lego_loam {

struct MapMatchResult {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  int edge_matches = 0;
  int plane_matches = 0;
  int iterations = 0;
  int degenerate_directions = 0;     // of the 6, held at the guess
  double smallest_eigenvalue = 0.0;  // of the normal equations at the first iteration
  bool matched = false;              // false with too few correspondences: pose = guess
  // What the LiDAR's correspondences alone say of the pose: their information about a right
  // perturbation of it ([rotation vector, translation], sensor frame), by the last iteration's
  // correspondences at the result, with MappingParams::residual_sigma. Zero when not matched.
  Matrix6d information = Matrix6d::Zero();
  bool motion_prior = false;  // the motion sensors' motion prior took part
  bool prior_from_imu = false, prior_from_wheel = false;  // what made it (MotionPrior's)
  // The pose kept the prediction along the direction the odometry's follow test held (the motion
  // model's), and `information` says nothing of it (LidarMapping::process).
  bool odometry_held = false;
  // What the motion sensors' priors added (the motion prior on the directions it held, gravity
  // on roll and pitch), in the units and frame of `information`.
  Matrix6d prior_information = Matrix6d::Zero();
  // How well the first iteration's correspondences fixed each direction (with residual_sigma),
  // when the motion sensors' prior was offered: it holds the directions they leave open.
  std::optional<Observability> lidar_observability;
};

// How the ambient filter sees the scene's structure before any match: the horizontal direction
// it constrains least (sensor frame) and how degenerate it is (mu).
struct SceneDegeneration {
  Eigen::Vector3d weak_direction = Eigen::Vector3d::UnitX();
  double mu = 0.0;
};

// The motion sensors' priors on a scan's pose (core/motion_sensors/): its motion since the
// previous scan's mapped pose `previous` (map frame), and gravity's up in the sensor frame against
// the map frame's up `map_up`. The motion prior holds the directions the correspondences leave
// open, their information along the scene's weak direction counted as 1 - mu of it.
struct SensorPriors {
  Eigen::Isometry3d previous = Eigen::Isometry3d::Identity();
  std::optional<MotionPrior> motion;
  std::optional<GravityPrior> gravity;
  Eigen::Vector3d map_up = Eigen::Vector3d::UnitZ();
  std::optional<SceneDegeneration> scene;
  bool empty() const { return !motion && !gravity; }
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
                  const std::vector<Eigen::Vector3d>& wall_normals = {},
                  const SensorPriors& sensors = SensorPriors());
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
  // params.vertical_prior_weight > 0. `sensors`: the motion sensors' priors, weighed against the
  // correspondences by params.residual_sigma.
  MapMatchResult match(const Cloud& corners, const Cloud& surfaces, const LocalMap& map,
                       const Eigen::Isometry3d& guess,
                       const std::optional<WeakDirectionPrior>& prior = std::nullopt,
                       const std::vector<Eigen::Vector3d>& wall_normals = {},
                       const SensorPriors& sensors = SensorPriors()) const;

 private:
  MappingParams params_;
};

}  // namespace adaptive_lego_loam
