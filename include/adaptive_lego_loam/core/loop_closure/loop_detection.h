#pragma once
// Loop detection: a candidate (an older keyframe of the same place, from place recognition or
// LeGO-LOAM's radius search) is checked by ICP of the newest keyframe's cloud against the
// candidate's neighbourhood, from the candidate's guess, and accepted on inliers
// (keyframe_graph.h closes the loop in the pose graph).

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"

namespace adaptive_lego_loam {

class SteppedIcp;

enum class LoopStatus {
  kAccepted,
  kDisabled,       // params.enabled is false
  kNoCandidate,    // no keyframe near enough and old enough
  kTooFewPoints,   // the current cloud or the candidate's map is (nearly) empty
  kNotConverged,   // ICP did not converge
  kTooFewInliers,  // ICP converged, but too few points fit the map, or not closely enough
  kBeyondDrift,    // verified, but it would move the map by more than the odometry can drift
};
const char* to_string(LoopStatus status);

enum class CandidateSource { kPlace, kRadius };
const char* to_string(CandidateSource source);

struct LoopCandidate {
  int matched_index = -1;
  CandidateSource source = CandidateSource::kRadius;
  // The current keyframe's pose in the map frame that ICP starts from.
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  double place_distance = 1.0;  // the descriptors' distance (place recognition)
};

struct LoopDetection {
  LoopStatus status = LoopStatus::kNoCandidate;
  int current_index = -1;
  int matched_index = -1;  // the candidate, once one was found
  CandidateSource source = CandidateSource::kRadius;
  // Once ICP ran: PCL's fitness (mean squared distance of every source point to the map), the
  // share of source points within inlier_distance and those inliers' mean squared distance.
  double fitness = std::numeric_limits<double>::infinity();  // m^2
  double inlier_ratio = 0.0;
  double inlier_mse = std::numeric_limits<double>::infinity();  // m^2
  int icp_iterations = 0;
  // How far the refinement moved the current keyframe from where ICP put it (m); 0 unrefined.
  double refinement_m = 0.0;
  // ICP's map-frame correction of the current keyframe: corrected pose = correction * pose.
  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  // T_matched^-1 * corrected T_current: the loop edge's measurement (when accepted).
  Eigen::Isometry3d relative_pose = Eigen::Isometry3d::Identity();
  double time_ms = 0.0;

  bool accepted() const { return status == LoopStatus::kAccepted; }
};

// LeGO-LOAM's candidate: the keyframe holding clouds, not degenerate, nearest to
// keyframes[current_index] (3-D distance between positions) within search_radius and with a stamp
// at least min_time_gap older, the guess the current pose; none when there is none. Ties go to
// the lower index.
std::optional<LoopCandidate> radius_candidate(const std::vector<Keyframe>& keyframes,
                                              int current_index, const LoopClosureParams& params);

// Aligns the current keyframe's points within verify_radius (corners + surfaces; every n-th
// point, at most icp_max_points), placed in the map frame by the candidate's guess, to the
// candidate's map: the candidate and up to neighbourhood_keyframes keyframes on either side of it
// (leaving out any less than min_time_gap older than the current one), in the map frame,
// voxel-filtered. Accepted when ICP converged with at least min_inlier_ratio of the points within
// inlier_distance of the map and their mean squared distance at most max_inlier_mse. Given
// `refinement` (mapping's params), an accepted loop's pose is then refined by ScanToMapMatcher:
// the current keyframe's corners and surfaces (every n-th, at most icp_max_points) to lines and
// planes of the candidate's map (its keyframes in a LocalMap); the refined pose when it matched,
// ICP's otherwise. Without a candidate: kNoCandidate. Throws std::out_of_range for a bad
// current_index.
LoopDetection detect_loop(const std::vector<Keyframe>& keyframes, int current_index,
                          const std::optional<LoopCandidate>& candidate,
                          const LoopClosureParams& params,
                          const std::optional<MappingParams>& refinement = std::nullopt);
// The same with radius_candidate().
LoopDetection detect_loop(const std::vector<Keyframe>& keyframes, int current_index,
                          const LoopClosureParams& params);

// The path driven from keyframe `first` to keyframe `last` (m, along the keyframes).
double path_between(const std::vector<Keyframe>& keyframes, int first, int last);

// Whether a candidate lies at least min_loop_path back along the path from the current keyframe:
// a loop returns after going somewhere. A drive that stands still, or whose odometry does (a
// tunnel's smooth walls), returns nowhere, however alike its keyframes look.
bool far_enough_along(const std::vector<Keyframe>& keyframes, int candidate, int current,
                      const LoopClosureParams& params);

// Whether an accepted loop moves its current keyframe, from where the odometry put it relative to
// the matched one, by at most max_drift_fraction of the path between them (along the keyframes)
// plus max_drift_offset: more than odometry drifts is a place that only looks the same.
bool within_drift_bound(const std::vector<Keyframe>& keyframes, const LoopDetection& loop,
                        const LoopClosureParams& params);

// detect_loop in bounded steps: the candidate's map a few keyframes at a time
// (params.map_points_per_scan), its voxel filter, its KD-tree, then params.icp_iterations_per_scan
// ICP iterations a step, the fitness taking the place of the last; refining an accepted loop, the
// refinement's map a few keyframes at a time again, then as many iterations of the match a step.
// Any step sizes give detect_loop's detection bit for bit: ICP and the match resume exactly where
// they stopped (an iteration at a time). The keyframes are read when the job is made: their
// poses as they are then (their clouds are shared, not copied).
class LoopDetectionJob {
 public:
  // Samples the current keyframe's cloud; throws std::out_of_range for a bad current_index.
  // Already done when there is nothing to align.
  LoopDetectionJob(const std::vector<Keyframe>& keyframes, int current_index,
                   const std::optional<LoopCandidate>& candidate, const LoopClosureParams& params,
                   const std::optional<MappingParams>& refinement = std::nullopt);
  ~LoopDetectionJob();
  LoopDetectionJob(LoopDetectionJob&&) noexcept;
  LoopDetectionJob& operator=(LoopDetectionJob&&) noexcept;

  // Does the next piece of the work; true once the detection is final (then does nothing).
  bool step();
  bool done() const;
  // Final once done(); time_ms adds up the time of the constructor and every step.
  const LoopDetection& detection() const { return detection_; }

 private:
  struct Work;
  void add_to_map();
  void filter_map();
  void prepare_icp();
  void iterate_icp();
  void conclude(SteppedIcp& icp);
  void add_to_refinement_map();
  void refine();
  void accept(const Eigen::Isometry3d& corrected);
  void finish(LoopStatus status);

  LoopClosureParams params_;
  std::optional<MappingParams> refinement_;
  LoopDetection detection_;
  std::unique_ptr<Work> work_;  // null once done
};

}  // namespace adaptive_lego_loam
