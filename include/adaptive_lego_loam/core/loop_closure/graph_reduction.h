#pragma once
// A long pose graph solved over a few of its nodes, so that a loop closure's solver iteration
// costs the same however long the run.

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/loop_closure/pose_graph.h"

namespace adaptive_lego_loam {

// A pose graph over some of another's nodes: at most max_nodes (unless the loops alone have more
// ends), all of them when there are no more. Kept: the first and the last node, both ends of every
// loop edge, and nodes evenly spaced between. Consecutive kept nodes are tied by the odometry
// edges between them composed: the product of their measurements, with the inverse of the sum of
// their covariances, each carried to the chain's end, as information. With every node kept it is
// the same graph, edges in the same order.
struct ReducedGraph {
  PoseGraph graph;
  std::vector<int> nodes;  // reduced node -> full node, ascending
};
// `full`'s edges other than loops must be odometry edges 0 -> 1, 1 -> 2, ... in that order (as
// KeyframeGraph makes them); std::invalid_argument otherwise.
ReducedGraph reduce_graph(const PoseGraph& full, int max_nodes);
// Every full node's pose from the reduced graph's solution: the kept nodes take theirs; a node
// between two kept ones follows both rigidly, blended by where it sits between them.
std::vector<Eigen::Isometry3d> expand_poses(const ReducedGraph& reduced, const PoseGraph& full);

}  // namespace adaptive_lego_loam
