#pragma once
// Loop closure on keyframes, as LeGO-LOAM: find an old keyframe near the newest one, check the
// match by ICP, and close the loop in a pose graph.
//
// Use from the mapping stage:
//   KeyframeGraph graph(params);
//   for each new keyframe:  keyframes.push_back(kf); graph.add_keyframe(kf);
//   periodically:
//     LoopDetection loop = detect_loop(keyframes, newest_index, params);
//     if (loop.accepted()) { graph.add_loop(loop); graph.optimize(keyframes); }
// optimize() rewrites every keyframe pose. The mapping's running pose estimate should then be
// moved with the newest keyframe: T <- T_newest_after * T_newest_before^-1 * T.
//
// A mapping that must bound its time per scan spreads the same work over the following scans:
// a LoopDetectionJob (one step() a scan) gives the detection, then a LoopOptimization (one step()
// a scan) the corrected poses, while keyframes keep being added.

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/core/keyframe.h"
#include "adaptive_lego_loam/core/params.h"
#include "adaptive_lego_loam/core/pose_graph.h"

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

// The keyframe nearest to keyframes[current_index] (3-D distance between positions) within
// search_radius and with a stamp at least min_time_gap older; -1 when there is none. Ties go to
// the lower index.
int find_loop_candidate(const std::vector<Keyframe>& keyframes, int current_index,
                        const LoopClosureParams& params);

// Finds a candidate and aligns the current keyframe's cloud (corners + surfaces + outliers, placed
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

// A pose graph kept alongside the keyframe list: node i is keyframe i.
class KeyframeGraph {
 public:
  explicit KeyframeGraph(const LoopClosureParams& params);

  // Adds the next keyframe (keyframe.index must equal the number added so far). From the second
  // on, it is tied to the previous one by an odometry edge measuring their poses as they are now.
  void add_keyframe(const Keyframe& keyframe);
  // Adds an accepted loop as a loop edge; throws std::invalid_argument otherwise.
  void add_loop(const LoopDetection& loop);
  // Optimises and writes the poses back into keyframes (whose size must equal the node count).
  PoseGraphSummary optimize(std::vector<Keyframe>& keyframes);
  // Sets every node's pose from its keyframe (sizes must match).
  void set_poses(const std::vector<Keyframe>& keyframes);

  const PoseGraph& graph() const { return graph_; }

 private:
  Information6 odometry_information_;
  Information6 loop_information_;
  PoseGraph graph_;
};

// add_loop and optimize in bounded steps, for a mapping that keeps adding keyframes meanwhile: a
// copy of the graph with the loop, reduced to params.graph_max_nodes nodes (reduce_graph), is
// optimised params.graph_iterations_per_scan solver iterations a step, each resuming where the
// last stopped, until it converges or has taken the pose graph's iteration limit
// (PoseGraphOptions::max_iterations).
class LoopOptimization {
 public:
  // `loop` must be accepted (std::invalid_argument otherwise).
  LoopOptimization(const KeyframeGraph& graph, const LoopDetection& loop,
                   const LoopClosureParams& params);

  // Runs the next iterations; true once finished (then does nothing).
  bool step();
  bool done() const { return done_; }
  const LoopDetection& loop() const { return loop_; }

  // Once done (std::logic_error before): adds the loop to `graph` and moves the keyframes the
  // optimisation covered to its poses and those added since rigidly with the last of them, the
  // graph's nodes with them. Returns that rigid motion (map frame: new pose = motion * old pose).
  Eigen::Isometry3d apply(KeyframeGraph& graph, std::vector<Keyframe>& keyframes) const;

 private:
  LoopDetection loop_;
  KeyframeGraph with_loop_;  // the graph and the loop, at the poses before
  ReducedGraph optimized_;
  int iterations_per_step_;
  int max_iterations_;
  int iterations_ = 0;
  double trust_region_radius_ = PoseGraphSummary::kInitialTrustRegionRadius;
  bool done_ = false;
};

}  // namespace adaptive_lego_loam
