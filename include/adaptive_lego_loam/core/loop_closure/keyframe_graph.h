#pragma once
// The pose graph of the keyframes, and the loop closures that enter it.
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
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/loop_closure/graph_reduction.h"
#include "adaptive_lego_loam/core/loop_closure/loop_detection.h"
#include "adaptive_lego_loam/core/loop_closure/pose_graph.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"

namespace adaptive_lego_loam {

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
  // Removes the loop edges whose residual at the current poses exceeds `sigmas`; returns how many.
  int remove_loops_off_by(double sigmas);
  int loops() const;

  const PoseGraph& graph() const { return graph_; }

 private:
  Information6 odometry_information_;
  Information6 loop_information_;
  PoseGraph graph_;
};

// add_loop and optimize in bounded steps, for a mapping that keeps adding keyframes meanwhile: a
// copy of the graph with the loops, reduced to params.graph_max_nodes nodes (reduce_graph), is
// optimised params.graph_iterations_per_scan solver iterations a step, each resuming where the
// last stopped, until it converges or has taken the pose graph's iteration limit
// (PoseGraphOptions::max_iterations). Without loops it solves the graph again as it is (after a
// loop was removed).
class LoopOptimization {
 public:
  // Every loop must be accepted (std::invalid_argument otherwise).
  LoopOptimization(const KeyframeGraph& graph, const std::vector<LoopDetection>& loops,
                   const LoopClosureParams& params);

  // Runs the next iterations; true once finished (then does nothing).
  bool step();
  bool done() const { return done_; }
  const std::vector<LoopDetection>& loops() const { return loops_; }

  // Once done (std::logic_error before): adds the loops to `graph` and moves the keyframes the
  // optimisation covered to its poses and those added since rigidly with the last of them, the
  // graph's nodes with them. Returns that rigid motion (map frame: new pose = motion * old pose).
  Eigen::Isometry3d apply(KeyframeGraph& graph, std::vector<Keyframe>& keyframes) const;

 private:
  std::vector<LoopDetection> loops_;
  KeyframeGraph with_loop_;  // the graph and the loop, at the poses before
  ReducedGraph optimized_;
  int iterations_per_step_;
  int max_iterations_;
  int iterations_ = 0;
  double trust_region_radius_ = PoseGraphSummary::kInitialTrustRegionRadius;
  bool done_ = false;
};

}  // namespace adaptive_lego_loam
