#pragma once
// Drifted odometry around a square and the pose graphs built from it, for the pose-graph tests.

#include <Eigen/Geometry>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "adaptive_lego_loam/core/loop_closure/pose_graph.h"
#include "support/poses.h"

namespace adaptive_lego_loam::test {

constexpr double kSigmaTranslation = 0.05;  // m, odometry and loop edges
constexpr double kSigmaRotation = 0.5 * kDeg;

// 40 poses 1 m apart around a 10 m square, counter-clockwise from the origin heading +x; the
// last is at (0, 1) heading -y, one step short of the start.
inline Poses square_truth() {
  Poses poses;
  for (int k = 0; k < 40; ++k) {
    const int side = k / 10;
    const double along = k % 10;
    const double corners[4][2] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const double directions[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    poses.push_back(planar(corners[side][0] + along * directions[side][0],
                           corners[side][1] + along * directions[side][1], 90.0 * side));
  }
  return poses;
}

inline Poses relative_steps(const Poses& poses) {
  Poses steps;
  for (std::size_t k = 1; k < poses.size(); ++k)
    steps.push_back(poses[k - 1].inverse() * poses[k]);
  return steps;
}

// Each step turned by an extra yaw_bias_deg and stretched by (1 + scale_error).
inline Poses drifted(const Poses& steps, double yaw_bias_deg, double scale_error) {
  Poses out;
  for (const Eigen::Isometry3d& step : steps) {
    Eigen::Isometry3d measured = step;
    measured.linear() = step.linear() * planar(0, 0, yaw_bias_deg).linear();
    measured.translation() = (1.0 + scale_error) * step.translation();
    out.push_back(measured);
  }
  return out;
}

inline Poses integrate(const Poses& steps) {
  Poses poses{Eigen::Isometry3d::Identity()};
  for (const Eigen::Isometry3d& step : steps)
    poses.push_back(poses.back() * step);
  return poses;
}

// Nodes at `poses`, tied by odometry edges from `steps`.
inline PoseGraph odometry_chain(const Poses& poses, const Poses& steps,
                                const PoseGraphOptions& options = PoseGraphOptions()) {
  PoseGraph graph(options);
  for (const Eigen::Isometry3d& pose : poses)
    graph.add_node(pose);
  const Information6 information = information_from_sigmas(kSigmaTranslation, kSigmaRotation);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    graph.add_edge(
        {static_cast<int>(k), static_cast<int>(k) + 1, steps[k], information, EdgeKind::kOdometry});
  }
  return graph;
}

// Nodes at `initial`, odometry edges from `steps`, a loop edge 0 -> last measuring `loop`.
inline PoseGraph square_graph(const Poses& initial, const Poses& steps,
                              const Eigen::Isometry3d& loop,
                              const PoseGraphOptions& options = PoseGraphOptions()) {
  PoseGraph graph = odometry_chain(initial, steps, options);
  const Information6 information = information_from_sigmas(kSigmaTranslation, kSigmaRotation);
  graph.add_edge({0, static_cast<int>(initial.size()) - 1, loop, information, EdgeKind::kLoop});
  return graph;
}

inline double max_position_change(const Poses& a, const Poses& b) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
    worst = std::max(worst, (a[k].translation() - b[k].translation()).norm());
  return worst;
}

struct DriftCase {
  Poses truth = square_truth();
  Poses odometry = drifted(relative_steps(truth), 0.25, 0.01);
  Poses initial = integrate(odometry);
  Eigen::Isometry3d true_loop = truth.front().inverse() * truth.back();
};

}  // namespace adaptive_lego_loam::test
