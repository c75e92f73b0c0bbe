#pragma once
// A pose graph over keyframe poses, solved with Ceres.
//
// Nodes are sensor poses in the map frame; node 0 is held fixed (it fixes the gauge). An edge is a
// measured relative pose Z = T_from^-1 * T_to with a 6x6 information matrix. Its residual is
//   r = L^T * log(Z^-1 * T_from^-1 * T_to),   L * L^T = information,
// where log is the SE(3) logarithm written as (rho, phi): phi the rotation vector of the error
// rotation (rad) and rho its translation after the SE(3) left-Jacobian inverse (m). Vectors and
// information matrices are ordered (x, y, z, rx, ry, rz): translation first.
//
// Loop edges (and optionally odometry edges) go through a robust loss applied to the whitened
// residual norm |r|, so that a wrong loop cannot drag the whole trajectory.
//
// Use: add_node() once per keyframe (indices 0, 1, ...), add_edge() for odometry and loops,
// optimize(), then read pose(i). optimize() starts from the current poses and overwrites them; it
// is deterministic (single-threaded, fixed solver options, problem built in insertion order).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"

namespace ceres {
class Problem;
}

namespace adaptive_lego_loam {

using Information6 = Eigen::Matrix<double, 6, 6>;

// Diagonal information for independent per-axis errors: translation sigma (m) on x, y, z and
// rotation sigma (rad) about x, y, z.
Information6 information_from_sigmas(double translation_sigma, double rotation_sigma_rad);

enum class EdgeKind { kOdometry, kLoop };

struct PoseGraphEdge {
  int from = 0;
  int to = 0;
  Eigen::Isometry3d measurement = Eigen::Isometry3d::Identity();  // T_from^-1 * T_to
  Information6 information = Information6::Identity();            // symmetric positive definite
  EdgeKind kind = EdgeKind::kOdometry;
};

struct PoseGraphOptions {
  RobustLoss loop_loss = RobustLoss::kCauchy;
  double loop_loss_scale = 2.0;  // in whitened units (sigmas)
  RobustLoss odometry_loss = RobustLoss::kNone;
  double odometry_loss_scale = 2.0;
  int max_iterations = 100;
};

struct PoseGraphSummary {
  bool converged = false;  // the solver met a convergence tolerance (also true with nothing to do)
  double initial_cost = 0.0;  // 1/2 sum of rho(|r|^2) over all edges
  double final_cost = 0.0;
  int iterations = 0;  // solver steps taken, successful or not
  double time_ms = 0.0;
  // Levenberg-Marquardt's trust-region radius at the end: a later optimize() resumes with it.
  double trust_region_radius = kInitialTrustRegionRadius;

  static constexpr double kInitialTrustRegionRadius = 1e4;  // Ceres' default
};

class PoseGraph {
 public:
  explicit PoseGraph(const PoseGraphOptions& options = PoseGraphOptions());

  // Adds a node with this initial pose and returns its index (0 for the first).
  int add_node(const Eigen::Isometry3d& pose);
  // Throws std::invalid_argument when a node index is unknown, from == to, or the information
  // matrix is not symmetric positive definite.
  void add_edge(const PoseGraphEdge& edge);

  const PoseGraphOptions& options() const { return options_; }
  int node_count() const { return static_cast<int>(nodes_.size()); }
  const std::vector<PoseGraphEdge>& edges() const { return edges_; }
  Eigen::Isometry3d pose(int node) const;
  std::vector<Eigen::Isometry3d> poses() const;
  // Replaces a node's pose (e.g. to start over from new estimates); node 0 stays fixed at
  // whatever it holds.
  void set_pose(int node, const Eigen::Isometry3d& pose);

  // The cost optimize() minimises, at the current poses.
  double cost() const;
  // An edge's whitened residual norm |r| (sigmas, before the robust loss), at the current poses.
  double residual_norm(int edge) const;
  void remove_edge(int edge);
  PoseGraphSummary optimize();
  // At most max_iterations solver steps, starting from this trust-region radius: a long
  // optimisation run in short calls, each starting with the previous call's
  // summary.trust_region_radius, takes nearly the steps one call would.
  PoseGraphSummary optimize(int max_iterations, double trust_region_radius);

 private:
  // A pose as Ceres parameter blocks: unit quaternion (x, y, z, w, Eigen's storage order) and
  // translation.
  struct Node {
    double rotation[4];
    double translation[3];
  };

  // Adds every node and edge, in insertion order, with `nodes` as the parameter blocks.
  void build_problem(std::vector<Node>& nodes, ceres::Problem& problem) const;

  PoseGraphOptions options_;
  std::vector<Node> nodes_;
  std::vector<PoseGraphEdge> edges_;
  std::vector<Information6> whitenings_;  // per edge: L^T with L * L^T = information
};

}  // namespace adaptive_lego_loam
