#pragma once
// Loop detection as LeGO-LOAM: an old keyframe near the newest one is a candidate, and ICP of the
// newest keyframe's cloud against the candidate's neighbourhood checks the match
// (keyframe_graph.h closes the loop in the pose graph).

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"

namespace adaptive_lego_loam {

enum class LoopStatus {
  kAccepted,
  kDisabled,      // params.enabled is false
  kNoCandidate,   // no keyframe near enough and old enough
  kTooFewPoints,  // the current cloud or the candidate's map is (nearly) empty
  kNotConverged,  // ICP did not converge
  kPoorFitness,   // ICP converged with fitness >= fitness_threshold
};
const char* to_string(LoopStatus status);

struct LoopDetection {
  LoopStatus status = LoopStatus::kNoCandidate;
  int current_index = -1;
  int matched_index = -1;                                    // the candidate, once one was found
  double fitness = std::numeric_limits<double>::infinity();  // m^2, once ICP ran
  int icp_iterations = 0;
  // ICP's map-frame correction of the current keyframe: corrected pose = correction * pose.
  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  // T_matched^-1 * corrected T_current: the loop edge's measurement (when accepted).
  Eigen::Isometry3d relative_pose = Eigen::Isometry3d::Identity();
  double time_ms = 0.0;

  bool accepted() const { return status == LoopStatus::kAccepted; }
};

// The keyframe holding clouds nearest to keyframes[current_index] (3-D distance between
// positions) within search_radius and with a stamp at least min_time_gap older; -1 when there is
// none. Ties go to the lower index.
int find_loop_candidate(const std::vector<Keyframe>& keyframes, int current_index,
                        const LoopClosureParams& params);

// Finds a candidate and aligns the current keyframe's cloud (corners + surfaces, placed
// in the map frame by its pose; every n-th point, at most icp_max_points) to the candidate's map:
// the candidate and up to neighbourhood_keyframes keyframes on either side of it (leaving out any
// less than min_time_gap older than the current one), in the map frame, voxel-filtered. Accepted
// when ICP converged with fitness below fitness_threshold. Throws std::out_of_range for a bad
// current_index.
LoopDetection detect_loop(const std::vector<Keyframe>& keyframes, int current_index,
                          const LoopClosureParams& params);

// detect_loop in bounded steps: the candidate's map a few keyframes at a time
// (params.map_points_per_scan), its voxel filter, its KD-tree, then params.icp_iterations_per_scan
// ICP iterations a step, the fitness taking the place of the last. Any step sizes give
// detect_loop's detection bit for bit: ICP resumes exactly where it stopped (an iteration at a
// time, from the cloud the last one left). The keyframes are read when the job is made: their
// poses as they are then (their clouds are shared, not copied).
class LoopDetectionJob {
 public:
  // Finds the candidate and samples the current keyframe's cloud; throws std::out_of_range for a
  // bad current_index. Already done when there is nothing to align.
  LoopDetectionJob(const std::vector<Keyframe>& keyframes, int current_index,
                   const LoopClosureParams& params);
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
  void conclude(double fitness, const Eigen::Matrix4f& transformation);
  void finish(LoopStatus status);

  LoopClosureParams params_;
  LoopDetection detection_;
  std::unique_ptr<Work> work_;  // null once done
};

}  // namespace adaptive_lego_loam
