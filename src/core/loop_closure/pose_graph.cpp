#include "adaptive_lego_loam/core/loop_closure/pose_graph.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/rotation.h>
#include <ceres/solver.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/core/common/timing.h"

namespace adaptive_lego_loam {
namespace {

template <typename T>
using Vector3 = Eigen::Matrix<T, 3, 1>;

// SE(3) logarithm of (q, t) as (rho, phi), translation first.
template <typename T>
Eigen::Matrix<T, 6, 1> se3_log(const Eigen::Quaternion<T>& q, const Vector3<T>& t) {
  const T wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  Vector3<T> phi;
  ceres::QuaternionToAngleAxis(wxyz, phi.data());
  const T theta_sq = phi.squaredNorm();
  // rho = V(phi)^-1 t with V^-1 = I - W/2 + c W^2, W = [phi]x and
  // c = (1 - (theta/2) cot(theta/2)) / theta^2; its series below avoids 0/0 at small angles.
  T c;
  if (theta_sq < T(1e-4)) {
    c = T(1.0 / 12.0) + theta_sq / T(720.0) + theta_sq * theta_sq / T(30240.0);
  } else {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T half = sqrt(theta_sq) / T(2.0);
    c = (T(1.0) - half * cos(half) / sin(half)) / theta_sq;
  }
  const Vector3<T> phi_x_t = phi.cross(t);
  Eigen::Matrix<T, 6, 1> log;
  log.template head<3>() = t - phi_x_t / T(2.0) + c * phi.cross(phi_x_t);
  log.template tail<3>() = phi;
  return log;
}

class RelativePoseResidual {
 public:
  RelativePoseResidual(const Eigen::Isometry3d& measurement, const Information6& sqrt_information)
      : measured_rotation_inverse_(Eigen::Quaterniond(measurement.rotation()).conjugate()),
        measured_translation_(measurement.translation()),
        sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* from_q, const T* from_t, const T* to_q, const T* to_t,
                  T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q_from(from_q), q_to(to_q);
    const Eigen::Map<const Vector3<T>> t_from(from_t), t_to(to_t);
    const Eigen::Quaternion<T> q_from_inverse = q_from.conjugate();
    // T_from^-1 * T_to, then Z^-1 * that.
    const Eigen::Quaternion<T> q_relative = q_from_inverse * q_to;
    const Vector3<T> t_relative = q_from_inverse * (t_to - t_from);
    const Eigen::Quaternion<T> z_inverse = measured_rotation_inverse_.template cast<T>();
    const Eigen::Quaternion<T> q_error = z_inverse * q_relative;
    const Vector3<T> t_error = z_inverse * (t_relative - measured_translation_.template cast<T>());
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_information_.template cast<T>() * se3_log(q_error, t_error);
    return true;
  }

 private:
  Eigen::Quaterniond measured_rotation_inverse_;
  Eigen::Vector3d measured_translation_;
  Information6 sqrt_information_;
};

// L^T with L * L^T = information, so that |L^T e|^2 = e^T information e.
Information6 whitening_of(const Information6& information) {
  if (!information.allFinite() || !information.isApprox(information.transpose(), 1e-9)) {
    throw std::invalid_argument("pose graph edge: information matrix is not symmetric");
  }
  const Eigen::LLT<Information6> llt(information);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("pose graph edge: information matrix is not positive definite");
  }
  return llt.matrixL().transpose();
}

ceres::LossFunction* make_loss(RobustLoss loss, double scale) {
  switch (loss) {
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(scale);
    case RobustLoss::kCauchy:
      return new ceres::CauchyLoss(scale);
    case RobustLoss::kNone:
      break;
  }
  return nullptr;
}

}  // namespace

Information6 information_from_sigmas(double translation_sigma, double rotation_sigma_rad) {
  if (!(translation_sigma > 0.0) || !(rotation_sigma_rad > 0.0)) {
    throw std::invalid_argument("information_from_sigmas: sigmas must be positive");
  }
  Eigen::Matrix<double, 6, 1> diagonal;
  diagonal.head<3>().setConstant(1.0 / (translation_sigma * translation_sigma));
  diagonal.tail<3>().setConstant(1.0 / (rotation_sigma_rad * rotation_sigma_rad));
  return diagonal.asDiagonal();
}

PoseGraph::PoseGraph(const PoseGraphOptions& options) : options_(options) {}

int PoseGraph::add_node(const Eigen::Isometry3d& pose) {
  nodes_.emplace_back();
  set_pose(node_count() - 1, pose);
  return node_count() - 1;
}

void PoseGraph::add_edge(const PoseGraphEdge& edge) {
  auto known = [&](int node) { return node >= 0 && node < node_count(); };
  if (!known(edge.from) || !known(edge.to) || edge.from == edge.to) {
    throw std::invalid_argument("pose graph edge " + std::to_string(edge.from) + " -> " +
                                std::to_string(edge.to) + ": needs two different nodes out of " +
                                std::to_string(node_count()));
  }
  whitenings_.push_back(whitening_of(edge.information));
  edges_.push_back(edge);
}

Eigen::Isometry3d PoseGraph::pose(int node) const {
  const Node& n = nodes_.at(node);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  // Normalised: the solver keeps the quaternion on the unit sphere only up to rounding.
  pose.linear() = Eigen::Quaterniond(n.rotation).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(n.translation);
  return pose;
}

std::vector<Eigen::Isometry3d> PoseGraph::poses() const {
  std::vector<Eigen::Isometry3d> all;
  all.reserve(nodes_.size());
  for (int i = 0; i < node_count(); ++i)
    all.push_back(pose(i));
  return all;
}

void PoseGraph::set_pose(int node, const Eigen::Isometry3d& pose) {
  Node& n = nodes_.at(node);
  Eigen::Map<Eigen::Quaterniond>(n.rotation) = Eigen::Quaterniond(pose.rotation()).normalized();
  Eigen::Map<Eigen::Vector3d>(n.translation) = pose.translation();
}

void PoseGraph::build_problem(std::vector<Node>& nodes, ceres::Problem& problem) const {
  for (Node& node : nodes) {
    problem.AddParameterBlock(node.rotation, 4, new ceres::EigenQuaternionManifold);
    problem.AddParameterBlock(node.translation, 3);
  }
  problem.SetParameterBlockConstant(nodes.front().rotation);
  problem.SetParameterBlockConstant(nodes.front().translation);
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const PoseGraphEdge& edge = edges_[i];
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseResidual, 6, 4, 3, 4, 3>(
        new RelativePoseResidual(edge.measurement, whitenings_[i]));
    ceres::LossFunction* loss =
        edge.kind == EdgeKind::kLoop
            ? make_loss(options_.loop_loss, options_.loop_loss_scale)
            : make_loss(options_.odometry_loss, options_.odometry_loss_scale);
    Node& from = nodes[edge.from];
    Node& to = nodes[edge.to];
    problem.AddResidualBlock(cost, loss, from.rotation, from.translation, to.rotation,
                             to.translation);
  }
}

double PoseGraph::residual_norm(int edge) const {
  const PoseGraphEdge& e = edges_.at(edge);
  const Node& from = nodes_[e.from];
  const Node& to = nodes_[e.to];
  const RelativePoseResidual residual(e.measurement, whitenings_[edge]);
  Eigen::Matrix<double, 6, 1> r;
  residual(from.rotation, from.translation, to.rotation, to.translation, r.data());
  return r.norm();
}

void PoseGraph::remove_edge(int edge) {
  edges_.erase(edges_.begin() + edge);
  whitenings_.erase(whitenings_.begin() + edge);
}

double PoseGraph::cost() const {
  if (edges_.empty()) return 0.0;
  std::vector<Node> nodes = nodes_;
  ceres::Problem problem;
  build_problem(nodes, problem);
  double total = 0.0;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &total, nullptr, nullptr, nullptr);
  return total;
}

PoseGraphSummary PoseGraph::optimize() {
  return optimize(options_.max_iterations, PoseGraphSummary::kInitialTrustRegionRadius);
}

PoseGraphSummary PoseGraph::optimize(int max_iterations, double trust_region_radius) {
  const Stopwatch stopwatch;
  PoseGraphSummary summary;
  if (edges_.empty()) {
    summary.converged = true;
    return summary;
  }
  ceres::Problem problem;
  build_problem(nodes_, problem);

  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.num_threads = 1;
  solver_options.max_num_iterations = max_iterations;
  solver_options.initial_trust_region_radius = trust_region_radius;
  solver_options.function_tolerance = 1e-10;
  solver_options.parameter_tolerance = 1e-10;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &problem, &ceres_summary);

  summary.converged = ceres_summary.termination_type == ceres::CONVERGENCE;
  summary.initial_cost = ceres_summary.initial_cost;
  summary.final_cost = ceres_summary.final_cost;
  summary.iterations = ceres_summary.num_successful_steps + ceres_summary.num_unsuccessful_steps;
  if (!ceres_summary.iterations.empty()) {
    summary.trust_region_radius = ceres_summary.iterations.back().trust_region_radius;
  }
  summary.time_ms = stopwatch.elapsed_ms();
  return summary;
}

}  // namespace adaptive_lego_loam
