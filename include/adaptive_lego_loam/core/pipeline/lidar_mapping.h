#pragma once
// LeGO-LOAM's mapOptimization on the core: every scan matched against a local map of the
// surrounding keyframes, keyframes by distance and angle, and the map frame's poses. The
// pipeline and the map_optimization node run this same class.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/loop_closure/keyframe_graph.h"
#include "adaptive_lego_loam/core/loop_closure/place_recognition.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"
#include "adaptive_lego_loam/core/mapping/keyframe_merging.h"
#include "adaptive_lego_loam/core/mapping/local_map.h"
#include "adaptive_lego_loam/core/mapping/map_gravity.h"
#include "adaptive_lego_loam/core/mapping/scan_to_map.h"
#include "adaptive_lego_loam/core/mapping/transform_fusion.h"
#include "adaptive_lego_loam/core/odometry/feature_extraction.h"
#include "adaptive_lego_loam/core/pipeline/localization_tracker.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {

struct MappingOutput {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // sensor in the map frame
  // The mapped motion since the previous scan (from the second scan on), without the jumps of
  // the map frame (a loop closed, an alignment in localization): the odometry's motion model.
  std::optional<Eigen::Isometry3d> motion;
  MapMatchResult match;
  bool keyframe = false;
  bool motion_gated = false;  // the odometry's motion was implausible: the guess kept the velocity
  // When a loop-closure attempt finished on this scan (it started at an earlier keyframe and ran
  // a bounded piece a scan since).
  std::optional<LoopDetection> loop;
  // Loops entered the pose graph on this scan, which moved the poses.
  bool loop_closed = false;
  // In localization mode.
  std::optional<LocalizationStatus> localization;
  StageTimes times;
};

// What loop closure has done so far.
struct LoopClosureCounts {
  int place_candidates = 0;   // attempts on a candidate from place recognition
  int radius_candidates = 0;  // ... from the radius search
  int verified = 0;           // accepted by ICP's inliers
  int rejected = 0;           // not accepted
  int beyond_drift = 0;       // verified, but a larger correction than the odometry can drift
  int unconfirmed = 0;        // verified, but no second loop agreed with it in time
  int closed = 0;             // entered the pose graph
  int removed = 0;            // later removed from it, inconsistent with the rest
};

class LidarMapping {
 public:
  explicit LidarMapping(const Config& config);
  // Localization on a saved map: `map` (keyframe i at position i) stays as it is; each scan is
  // matched against its keyframes and this drive's newest few (config.localization), from
  // `start`, the first scan's pose in the map frame. No loop closure, no merging.
  LidarMapping(const Config& config, std::vector<Keyframe> map, const Eigen::Isometry3d& start);
  // `odometry_pose`: the scan's pose in the odometry frame; the map pose is predicted from the
  // odometry's motion since the previous scan, then refined against the local map. `sensors`:
  // the motion sensors' prediction of this scan (its motion and gravity priors), if any.
  // `odometry_held`: the direction the odometry kept at its guess (OdometryResult::held_direction,
  // the previous scan's frame): scan-to-map keeps the motion along it as predicted too.
  void process(const FeatureSet& features, const Eigen::Isometry3d& odometry_pose, double stamp,
               const std::optional<WeakDirectionPrior>& prior, MappingOutput& out,
               const MotionPrediction* sensors = nullptr,
               const std::optional<SceneDegeneration>& scene = std::nullopt,
               const std::optional<Eigen::Vector3d>& odometry_held = std::nullopt);

  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  bool localizing() const { return localization_.has_value(); }
  // Localization mode: the first this many of keyframes() are the saved map's, the rest this
  // drive's (poses only, but for the newest few). 0 when mapping.
  int map_keyframes() const { return localization_ ? localization_->map_keyframes() : 0; }
  // Localization mode: the next scan is aligned to the map from `pose` (a new initial pose).
  void relocalize(const Eigen::Isometry3d& pose);
  const LocalMap& local_map() const { return local_map_; }
  const TransformFusion& fusion() const { return fusion_; }
  int loops_closed() const { return counts_.closed - counts_.removed; }
  const LoopClosureCounts& loop_closure_counts() const { return counts_; }
  bool loop_closure_running() const { return loop_job_ || loop_optimization_; }
  // Finishes the loop closure in progress at once (at the end of the input, where no scan is left
  // to spread it over): the attempt, and the pose graph if it closes loops; returns the attempt,
  // if there was one.
  std::optional<LoopDetection> finish_loop_closure();
  // Every scan's pose, re-derived from its keyframe so that later keyframe corrections apply;
  // empty when not kept.
  std::vector<Eigen::Isometry3d> trajectory() const;
  // Whether trajectory() is kept: on by default; a node that runs for hours turns it off, since
  // it costs every scan about 150 bytes.
  void keep_trajectory(bool keep) { keeps_trajectory_ = keep; }

 private:
  bool motion_is_plausible(const Eigen::Isometry3d& motion) const;
  // Whether this scan's guess keeps the last mapped motion (counts the scans gated in a row).
  bool gate_motion(const Eigen::Isometry3d& motion);
  bool needs_keyframe() const;
  void add_keyframe(const FeatureSet& features, double stamp, bool degenerate);
  Keyframe make_keyframe(const FeatureSet& features, double stamp, const Eigen::Isometry3d& pose,
                         bool degenerate);
  // Localization mode: the scan's map pose from `pose` (the prediction), aligned or matched;
  // returns whether it may become a keyframe (it is tracked).
  bool localize(const FeatureSet& features, const Cloud& corners, const Cloud& surfaces,
                double stamp, const std::optional<WeakDirectionPrior>& prior,
                const SensorPriors& sensor_priors, Eigen::Isometry3d& pose, MappingOutput& out);
  // The motion sensors' priors of this scan, mapped from the previous scan's pose.
  SensorPriors sensor_priors(const MotionPrediction* sensors,
                             const std::optional<SceneDegeneration>& scene) const;
  // This drive's keyframes but the newest `keep` give their clouds back (localization mode).
  void retire_recent_keyframes(int keep);
  // ... and then leave the list (localization mode).
  void drop_retired_keyframes();
  // A loop-closure attempt starts with a new keyframe that has a loop candidate, at most once a
  // second of data (LeGO-LOAM's rate) and one at a time; every scan then runs one bounded step of
  // it: the detection's, then, when accepted, the pose graph's. Returns the attempt on the scan
  // it finished.
  std::optional<LoopDetection> advance_loop_closure(double stamp, bool new_keyframe);
  void start_loop_closure(double stamp);
  // A verified loop waits for a second that agrees; the pair goes to the pose graph.
  void confirm(const LoopDetection& loop);
  bool loops_agree(const LoopDetection& first, const LoopDetection& second) const;
  // Applies the finished optimisation: keyframes, the running pose and the local map move.
  void close_loop();

  MappingParams params_;
  LoopClosureParams loop_params_;
  LocalizationParams localization_params_;
  std::optional<LocalizationTracker> localization_;
  // The first sweep of a sensor whose driver does not de-skew cannot be de-skewed (no motion is
  // known yet): a keyframe of it would bend the map for as long as it stays in it.
  bool first_sweep_distorted_;
  KeyframeGraph graph_;
  std::optional<LoopDetectionJob> loop_job_;
  std::optional<LoopOptimization> loop_optimization_;
  double last_loop_attempt_ = -1e18;
  double last_closure_ = -1e18;
  double last_stamp_ = 0.0;
  PlaceRecognition places_;
  std::vector<LoopDetection> pending_;  // verified loops waiting for one that agrees
  LoopClosureCounts counts_;
  bool closed_on_this_scan_ = false;
  LocalMap local_map_;
  KeyframeMerger merger_;
  ScanToMapMatcher matcher_;
  TransformFusion fusion_;
  // Their tables sized by what each filters: the scan's few coarse voxels, a keyframe's many.
  VoxelFilter scan_filter_, keyframe_filter_;
  std::vector<Keyframe> keyframes_;
  std::vector<Eigen::Vector3d> wall_normals_;  // this scan's, for the vertical-structure prior
  MapGravity map_gravity_;
  int scans_ = 0;
  std::optional<Eigen::Isometry3d> last_odometry_pose_;
  std::optional<Eigen::Isometry3d> last_mapped_motion_;
  int gated_in_a_row_ = 0;
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
  // Per scan: the keyframe it hangs from and its pose relative to that keyframe (-1 and the pose
  // itself before the first keyframe).
  std::vector<std::pair<int, Eigen::Isometry3d>> anchors_;
  bool keeps_trajectory_ = true;
};

}  // namespace adaptive_lego_loam
