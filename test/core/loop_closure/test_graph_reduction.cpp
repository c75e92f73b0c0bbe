#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "adaptive_lego_loam/core/loop_closure/graph_reduction.h"
#include "core/loop_closure/drifted_graphs.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

// n poses 1 m apart around a circle, heading along it; the last one step short of the start.
Poses circle_truth(int n) {
  Poses poses;
  const double radius = n / (2.0 * M_PI);
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * M_PI * k / n;
    poses.push_back(
        planar(radius * std::sin(angle), radius * (1.0 - std::cos(angle)), angle / kDeg));
  }
  return poses;
}

}  // namespace

TEST(ReducedGraph, WithRoomForEveryNodeIsTheSameGraph) {
  const DriftCase drift;
  PoseGraph full = square_graph(drift.initial, drift.odometry, drift.true_loop);
  ReducedGraph reduced = reduce_graph(full, 40);
  ASSERT_EQ(reduced.graph.node_count(), full.node_count());
  ASSERT_EQ(reduced.graph.edges().size(), full.edges().size());
  full.optimize();
  reduced.graph.optimize();
  const Poses expanded = expand_poses(reduced, full);
  for (int k = 0; k < full.node_count(); ++k)
    EXPECT_TRUE(expanded[k].isApprox(full.pose(k), 1e-12)) << k;
}

TEST(ReducedGraph, ALongLoopOverAFewNodesLandsOnTheFullSolution) {
  // 600 keyframes, the odometry turning 0.05 deg and stretching 1 % a step: the loop end is 46 m
  // off. Solved over 60 nodes, every keyframe lands within a few cm of where the full graph puts
  // it (dividing the composed edges' information by their count instead of carrying their
  // covariances along the chain leaves 0.8 m).
  const Poses truth = circle_truth(600);
  const Poses odometry = drifted(relative_steps(truth), 0.05, 0.01);
  const Poses initial = integrate(odometry);
  const Eigen::Isometry3d true_loop = truth.front().inverse() * truth.back();
  PoseGraph full = square_graph(initial, odometry, true_loop);
  const double drift_m = (initial.back().translation() - truth.back().translation()).norm();
  ASSERT_GT(drift_m, 3.0);

  ReducedGraph reduced = reduce_graph(full, 60);
  EXPECT_LE(reduced.graph.node_count(), 60);
  EXPECT_EQ(reduced.nodes.front(), 0);
  EXPECT_EQ(reduced.nodes.back(), 599);
  reduced.graph.optimize();
  const Poses expanded = expand_poses(reduced, full);
  ASSERT_EQ(static_cast<int>(expanded.size()), full.node_count());
  full.optimize();
  const Poses solved = full.poses();
  EXPECT_LT(max_position_change(expanded, solved), 0.05);
  double worst_deg = 0.0;
  for (std::size_t k = 0; k < solved.size(); ++k) {
    worst_deg = std::max(
        worst_deg,
        Eigen::AngleAxisd(solved[k].rotation().transpose() * expanded[k].rotation()).angle() /
            kDeg);
  }
  EXPECT_LT(worst_deg, 0.1);
  std::printf("drift %.2f m; reduced vs full: %.4f m, %.4f deg\n", drift_m,
              max_position_change(expanded, solved), worst_deg);
}

TEST(ReducedGraph, KeepsEveryLoopsEndsAndRejectsOdometryThatIsNotOneChain) {
  const DriftCase drift;
  PoseGraph full = square_graph(drift.initial, drift.odometry, drift.true_loop);
  const Information6 information = information_from_sigmas(kSigmaTranslation, kSigmaRotation);
  full.add_edge(
      {7, 23, drift.initial[7].inverse() * drift.initial[23], information, EdgeKind::kLoop});
  const ReducedGraph reduced = reduce_graph(full, 12);
  for (int node : {0, 7, 23, 39}) {
    EXPECT_NE(std::find(reduced.nodes.begin(), reduced.nodes.end(), node), reduced.nodes.end())
        << node;
  }
  EXPECT_LE(reduced.graph.node_count(), 12);

  PoseGraph skipping = full;
  skipping.add_edge(
      {3, 5, drift.initial[3].inverse() * drift.initial[5], information, EdgeKind::kOdometry});
  EXPECT_THROW(reduce_graph(skipping, 12), std::invalid_argument);
  PoseGraph repeated = full;  // 3 -> 4 again, after 38 -> 39
  repeated.add_edge(
      {3, 4, drift.initial[3].inverse() * drift.initial[4], information, EdgeKind::kOdometry});
  EXPECT_THROW(reduce_graph(repeated, 12), std::invalid_argument);
}
