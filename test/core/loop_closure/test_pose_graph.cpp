#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "adaptive_lego_loam/core/loop_closure/pose_graph.h"
#include "core/loop_closure/drifted_graphs.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

// The residual is the SE(3) logarithm of the error, whitened: moving the far node by exp(xi)
// away from the measurement costs exactly 1/2 xi^T information xi, for any coupled information.
TEST(PoseGraph, ResidualIsWhitenedSe3Log) {
  Eigen::Matrix<double, 6, 1> xi;
  xi << 0.3, -0.2, 0.5, 0.4, -0.25, 0.6;  // rho (m), phi (rad): a 0.76 rad turn
  Eigen::Matrix4d twist = Eigen::Matrix4d::Zero();
  twist.topLeftCorner<3, 3>() << 0, -xi(5), xi(4), xi(5), 0, -xi(3), -xi(4), xi(3), 0;
  twist.topRightCorner<3, 1>() = xi.head<3>();
  const Eigen::Isometry3d error(Eigen::Matrix4d(twist.exp()));

  Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Identity();
  a(0, 3) = 0.5;
  a(2, 4) = -0.3;
  a(1, 5) = 0.2;
  const Information6 information = a * a.transpose() * 40.0;
  const Eigen::Isometry3d measurement = planar(2.0, 1.0, 30.0);

  PoseGraph graph;
  graph.add_node(planar(-1.0, 4.0, -70.0));
  graph.add_node(graph.pose(0) * measurement * error);
  graph.add_edge({0, 1, measurement, information, EdgeKind::kOdometry});
  const double expected = 0.5 * xi.dot(information * xi);
  EXPECT_NEAR(graph.cost(), expected, 1e-9 * expected);
}

TEST(PoseGraph, ConsistentEdgesLeavePosesUnchanged) {
  const Poses truth = square_truth();
  PoseGraph graph =
      square_graph(truth, relative_steps(truth), truth.front().inverse() * truth.back());
  const PoseGraphSummary summary = graph.optimize();
  EXPECT_TRUE(summary.converged);
  EXPECT_LT(summary.final_cost, 1e-20);
  EXPECT_LT(max_position_change(graph.poses(), truth), 1e-9);
  for (int k = 0; k < graph.node_count(); ++k) {
    EXPECT_TRUE(graph.pose(k).linear().isApprox(truth[k].linear(), 1e-9)) << "node " << k;
  }
}

// Odometry turns 0.25 deg too far and stretches 1 % per 1 m step: 9.75 deg and 1.1 m off after
// the square. One loop edge with the true pose of the last node seen from the first pulls
// the end back. Bound: at the optimum the cost is at most the cost at the true poses, F_true (the
// solver must reach that basin). The loop edge alone costs 1/2 rho(u^2) with u its whitened
// residual and rho the Cauchy loss, so u^2 <= rho^-1(2 F_true) = a^2 (exp(2 F_true / a^2) - 1).
// The loop's error transform is T_last_true^-1 T_last, whose translation (the end position
// error) is at most sigma_t * u: |V(phi)| <= 1 in rho = V^-1 t.
TEST(PoseGraph, LoopEdgeRemovesDriftWithinCostBound) {
  const DriftCase drift;
  PoseGraph graph = square_graph(drift.initial, drift.odometry, drift.true_loop);
  const double cost_at_truth = square_graph(drift.truth, drift.odometry, drift.true_loop).cost();
  const PoseGraphSummary summary = graph.optimize();

  const double a = PoseGraphOptions().loop_loss_scale;
  const double u_max = a * std::sqrt(std::exp(2.0 * cost_at_truth / (a * a)) - 1.0);
  const double bound = kSigmaTranslation * u_max;
  const double odometry_error =
      (drift.initial.back().translation() - drift.truth.back().translation()).norm();
  const double end_error = (graph.pose(39).translation() - drift.truth.back().translation()).norm();
  std::printf(
      "[ measured ] odometry end error %.3f m, after loop %.4f m (bound %.3f m), "
      "F_true %.3f, final cost %.3f, %d iterations\n",
      odometry_error, end_error, bound, cost_at_truth, summary.final_cost, summary.iterations);
  EXPECT_TRUE(summary.converged);
  EXPECT_LE(summary.final_cost, cost_at_truth);
  EXPECT_GT(odometry_error, 1.0);
  EXPECT_LT(end_error, bound);
}

// An optimisation run one solver iteration a call, each resuming with the trust region the last
// one left, reaches the optimum one call reaches (within the solver's tolerances) in about as
// many iterations.
TEST(PoseGraph, OptimisationResumedOneIterationACallReachesTheSameOptimum) {
  const DriftCase drift;
  PoseGraph whole = square_graph(drift.initial, drift.odometry, drift.true_loop);
  const PoseGraphSummary at_once = whole.optimize();
  PoseGraph resumed = square_graph(drift.initial, drift.odometry, drift.true_loop);
  double radius = PoseGraphSummary::kInitialTrustRegionRadius;
  int calls = 0;
  for (bool converged = false; !converged && calls < PoseGraphOptions().max_iterations; ++calls) {
    const PoseGraphSummary summary = resumed.optimize(1, radius);
    EXPECT_LE(summary.iterations, 2) << "iteration 0 and one step";
    radius = summary.trust_region_radius;
    converged = summary.converged;
  }
  std::printf("[ measured ] one call: %d iterations; resumed: %d calls, cost %.6f vs %.6f\n",
              at_once.iterations, calls, resumed.cost(), at_once.final_cost);
  EXPECT_TRUE(at_once.converged);
  EXPECT_LE(calls, at_once.iterations + 2);
  EXPECT_NEAR(resumed.cost(), at_once.final_cost, 1e-6 * at_once.final_cost);
  EXPECT_LT(max_position_change(resumed.poses(), whole.poses()), 1e-4);
}

namespace {

// Odometry-only cost at `poses` as a distance: sqrt(2 F_odometry), in odometry sigmas.
double odometry_deformation(const Poses& poses, const Poses& steps) {
  return std::sqrt(2.0 * odometry_chain(poses, steps).cost());
}

// How far the loop measurement is from what the odometry says, in odometry sigmas: the least
// deformation of the odometry chain that makes the loop hold exactly (a nearly rigid loop edge).
double loop_mahalanobis(const Poses& initial, const Poses& steps, const Eigen::Isometry3d& loop) {
  PoseGraphOptions options;
  options.loop_loss = RobustLoss::kNone;
  PoseGraph graph = odometry_chain(initial, steps, options);
  graph.add_edge({0, static_cast<int>(initial.size()) - 1, loop,
                  information_from_sigmas(1e-6, 1e-8), EdgeKind::kLoop});
  graph.optimize();
  return odometry_deformation(graph.poses(), steps);
}

// The Cauchy loss is a consistency gate. With the loop far stiffer than the accumulated odometry,
// a loop disagreeing with the odometry by m sigmas (Mahalanobis) pulls against a tail force that
// falls as 1/m; a one-dimensional balance of the two has a second, spurious minimum near the
// odometry once m > 2 a. So the same true loop closes with a scale above m / 2 and stays open
// with one below (measured: closes from a = 0.93 m / 2 on).

}  // namespace

TEST(PoseGraph, CauchyScaleGatesLoopsByMahalanobisDistance) {
  const Poses truth = square_truth();
  const Poses odometry = drifted(relative_steps(truth), 0.5, 0.01);
  const Poses initial = integrate(odometry);
  const Eigen::Isometry3d true_loop = truth.front().inverse() * truth.back();
  const double m = loop_mahalanobis(initial, odometry, true_loop);
  auto end_error = [&](double scale) {
    PoseGraphOptions options;
    options.loop_loss_scale = scale;
    PoseGraph graph = square_graph(initial, odometry, true_loop, options);
    graph.optimize();
    return (graph.pose(39).translation() - truth.back().translation()).norm();
  };
  const double odometry_error = (initial.back().translation() - truth.back().translation()).norm();
  const double closed = end_error(1.2 * m / 2);
  const double open = end_error(0.75 * m / 2);
  std::printf(
      "[ measured ] loop %.2f sigmas off odometry (%.2f m): end error %.4f m with "
      "a = 0.6*m, %.3f m with a = 0.375*m\n",
      m, odometry_error, closed, open);
  EXPECT_LT(closed, 0.01);
  EXPECT_GT(open, 0.5 * odometry_error);
}

// A loop edge claiming the last node is 3 m and 30 deg away from where it is. Odometry is exact
// and the nodes start at the truth, so any motion is the outlier's doing. Without a loss the
// odometry chain bends by about the outlier's Mahalanobis distance m; the Cauchy tail force
// balances at a^2 / m sigmas (one-dimensional picture), so the chain must stay within one
// odometry sigma of its own measurements.
TEST(PoseGraph, RobustLossDownWeightsWrongLoop) {
  const Poses truth = square_truth();
  const Poses steps = relative_steps(truth);
  const Eigen::Isometry3d wrong_loop =
      truth.front().inverse() * truth.back() * planar(3.0, 0.0, 30.0);
  struct Effect {
    double deformation, displacement;
  };
  auto effect = [&](RobustLoss loss) {
    PoseGraphOptions options;
    options.loop_loss = loss;
    PoseGraph graph = square_graph(truth, steps, wrong_loop, options);
    EXPECT_TRUE(graph.optimize().converged);
    return Effect{odometry_deformation(graph.poses(), steps),
                  max_position_change(graph.poses(), truth)};
  };
  const double m = loop_mahalanobis(truth, steps, wrong_loop);
  const Effect plain = effect(RobustLoss::kNone);
  const Effect huber = effect(RobustLoss::kHuber);
  const Effect cauchy = effect(RobustLoss::kCauchy);
  const double a = PoseGraphOptions().loop_loss_scale;
  std::printf(
      "[ measured ] wrong loop %.1f sigmas off: odometry bent by %.2f / %.2f / %.3f "
      "sigmas (a^2/m = %.3f), poses moved up to %.3f / %.3f / %.4f m "
      "(no loss / Huber / Cauchy)\n",
      m, plain.deformation, huber.deformation, cauchy.deformation, a * a / m, plain.displacement,
      huber.displacement, cauchy.displacement);
  EXPECT_GT(plain.deformation, 0.9 * m);
  EXPECT_LT(huber.deformation, plain.deformation);
  EXPECT_LT(cauchy.deformation, 1.0);
  EXPECT_LT(cauchy.displacement, 0.1 * plain.displacement);
}

TEST(PoseGraph, SameInputsGiveBitIdenticalPoses) {
  const DriftCase drift;
  PoseGraph first = square_graph(drift.initial, drift.odometry, drift.true_loop);
  PoseGraph second = square_graph(drift.initial, drift.odometry, drift.true_loop);
  first.optimize();
  second.optimize();
  for (int k = 0; k < first.node_count(); ++k) {
    EXPECT_EQ(std::memcmp(first.pose(k).matrix().data(), second.pose(k).matrix().data(),
                          16 * sizeof(double)),
              0)
        << "node " << k;
  }
}

TEST(PoseGraph, FirstNodeStaysFixed) {
  const DriftCase drift;
  Poses initial = drift.initial;
  for (Eigen::Isometry3d& pose : initial)
    pose = planar(5.0, -3.0, 40.0) * pose;  // the whole chain somewhere else
  PoseGraph graph = square_graph(initial, drift.odometry, drift.true_loop);
  graph.optimize();
  EXPECT_TRUE(graph.pose(0).isApprox(initial[0], 1e-12));
  EXPECT_GT(max_position_change(graph.poses(), initial), 0.5);
}

TEST(PoseGraph, RejectsBadEdges) {
  PoseGraph graph;
  graph.add_node(Eigen::Isometry3d::Identity());
  graph.add_node(planar(1, 0, 0));
  const Information6 good = Information6::Identity();
  EXPECT_THROW(graph.add_edge({0, 2, Eigen::Isometry3d::Identity(), good, EdgeKind::kOdometry}),
               std::invalid_argument);
  EXPECT_THROW(graph.add_edge({1, 1, Eigen::Isometry3d::Identity(), good, EdgeKind::kOdometry}),
               std::invalid_argument);
  Information6 singular = good;
  singular(5, 5) = 0.0;
  EXPECT_THROW(graph.add_edge({0, 1, Eigen::Isometry3d::Identity(), singular, EdgeKind::kOdometry}),
               std::invalid_argument);
  Information6 asymmetric = good;
  asymmetric(0, 1) = 0.5;
  EXPECT_THROW(
      graph.add_edge({0, 1, Eigen::Isometry3d::Identity(), asymmetric, EdgeKind::kOdometry}),
      std::invalid_argument);
  EXPECT_TRUE(graph.edges().empty());
  EXPECT_THROW(information_from_sigmas(0.0, 0.1), std::invalid_argument);
}

TEST(PoseGraph, ResidualOfAnEdgeAndItsRemoval) {
  PoseGraph graph;
  graph.add_node(Eigen::Isometry3d::Identity());
  graph.add_node(planar(1, 0, 0));
  const Information6 information = information_from_sigmas(0.1, 1.0 * kDeg);
  graph.add_edge({0, 1, planar(1, 0, 0), information, EdgeKind::kOdometry});
  graph.add_edge({0, 1, planar(1.3, 0, 0), information, EdgeKind::kLoop});
  EXPECT_NEAR(graph.residual_norm(0), 0.0, 1e-9) << "the poses meet the odometry exactly";
  EXPECT_NEAR(graph.residual_norm(1), 3.0, 1e-6) << "0.3 m off at 0.1 m sigma";
  graph.remove_edge(1);
  ASSERT_EQ(graph.edges().size(), 1u);
  EXPECT_EQ(graph.edges()[0].kind, EdgeKind::kOdometry);
}
