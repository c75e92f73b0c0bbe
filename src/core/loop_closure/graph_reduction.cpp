#include "adaptive_lego_loam/core/loop_closure/graph_reduction.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam {

namespace {

// The adjoint of T on twists ordered (translation, rotation), as the residual orders them.
Eigen::Matrix<double, 6, 6> adjoint(const Eigen::Isometry3d& t) {
  const Eigen::Matrix3d rotation = t.rotation();
  const Eigen::Vector3d p = t.translation();
  Eigen::Matrix3d p_cross;
  p_cross << 0.0, -p.z(), p.y(), p.z(), 0.0, -p.x(), -p.y(), p.x(), 0.0;
  Eigen::Matrix<double, 6, 6> ad = Eigen::Matrix<double, 6, 6>::Zero();
  ad.topLeftCorner<3, 3>() = rotation;
  ad.topRightCorner<3, 3>() = p_cross * rotation;
  ad.bottomRightCorner<3, 3>() = rotation;
  return ad;
}

// Which of the full graph's nodes the reduced graph keeps (see ReducedGraph).
std::vector<char> nodes_to_keep(const PoseGraph& full, int max_nodes) {
  const int count = full.node_count();
  std::vector<char> keep(count, 0);
  if (count <= max_nodes) {
    keep.assign(count, 1);
    return keep;
  }
  int fixed = 0;
  auto mark = [&](int node) {
    if (!keep[node]) ++fixed;
    keep[node] = 1;
  };
  mark(0);
  mark(count - 1);
  for (const PoseGraphEdge& edge : full.edges()) {
    if (edge.kind == EdgeKind::kLoop) {
      mark(edge.from);
      mark(edge.to);
    }
  }
  const int spaced = std::max(1, max_nodes - fixed);
  const int stride = (count + spaced - 1) / spaced;
  for (int node = 0; node < count; node += stride)
    keep[node] = 1;
  return keep;
}

}  // namespace

ReducedGraph reduce_graph(const PoseGraph& full, int max_nodes) {
  const std::vector<char> keep = nodes_to_keep(full, max_nodes);
  ReducedGraph reduced{PoseGraph(full.options()), {}};
  std::vector<int> reduced_index(full.node_count(), -1);
  for (int node = 0; node < full.node_count(); ++node) {
    if (!keep[node]) continue;
    reduced_index[node] = reduced.graph.add_node(full.pose(node));
    reduced.nodes.push_back(node);
  }
  // The odometry edges since the last kept node, composed, with the covariance of the composition
  // (each edge's error is a twist at its far end: carried to the chain's end by the adjoint).
  Eigen::Isometry3d chain = Eigen::Isometry3d::Identity();
  int chain_from = 0, chain_edges = 0, odometry_reached = 0;
  Information6 chain_covariance = Information6::Zero();
  for (const PoseGraphEdge& edge : full.edges()) {
    if (edge.kind == EdgeKind::kLoop) {
      PoseGraphEdge loop = edge;
      loop.from = reduced_index[edge.from];
      loop.to = reduced_index[edge.to];
      reduced.graph.add_edge(loop);
      continue;
    }
    if (edge.to != edge.from + 1 || edge.from != odometry_reached) {
      throw std::invalid_argument(
          "reduce_graph: odometry edge " + std::to_string(edge.from) + " -> " +
          std::to_string(edge.to) + ", expected " + std::to_string(odometry_reached) + " -> " +
          std::to_string(odometry_reached + 1) + " (a chain through every node in order)");
    }
    odometry_reached = edge.to;
    if (chain_edges == 0) {
      chain_from = edge.from;
      chain = Eigen::Isometry3d::Identity();
      chain_covariance.setZero();
    }
    const Eigen::Matrix<double, 6, 6> carry = adjoint(edge.measurement.inverse());
    chain_covariance = carry * chain_covariance * carry.transpose() + edge.information.inverse();
    chain = chain * edge.measurement;
    ++chain_edges;
    if (!keep[edge.to]) continue;
    PoseGraphEdge composed;
    composed.from = reduced_index[chain_from];
    composed.to = reduced_index[edge.to];
    composed.measurement = chain;
    if (chain_edges == 1) {
      composed.information = edge.information;
    } else {
      const Information6 information = chain_covariance.inverse();
      composed.information = 0.5 * (information + information.transpose());
    }
    composed.kind = EdgeKind::kOdometry;
    reduced.graph.add_edge(composed);
    chain_edges = 0;
  }
  return reduced;
}

std::vector<Eigen::Isometry3d> expand_poses(const ReducedGraph& reduced, const PoseGraph& full) {
  std::vector<Eigen::Isometry3d> poses = full.poses();
  for (std::size_t k = 0; k < reduced.nodes.size(); ++k)
    poses[reduced.nodes[k]] = reduced.graph.pose(static_cast<int>(k));
  for (std::size_t k = 0; k + 1 < reduced.nodes.size(); ++k) {
    const int first = reduced.nodes[k], last = reduced.nodes[k + 1];
    // Each end's correction (new pose * old pose^-1), applied to the nodes between.
    const Eigen::Isometry3d first_correction = poses[first] * full.pose(first).inverse();
    const Eigen::Isometry3d last_correction = poses[last] * full.pose(last).inverse();
    for (int node = first + 1; node < last; ++node) {
      const double along = static_cast<double>(node - first) / (last - first);
      const Eigen::Isometry3d old_pose = full.pose(node);
      const Eigen::Isometry3d with_first = first_correction * old_pose;
      const Eigen::Isometry3d with_last = last_correction * old_pose;
      Eigen::Isometry3d blended = Eigen::Isometry3d::Identity();
      blended.linear() = Eigen::Quaterniond(with_first.rotation())
                             .slerp(along, Eigen::Quaterniond(with_last.rotation()))
                             .toRotationMatrix();
      blended.translation() =
          (1.0 - along) * with_first.translation() + along * with_last.translation();
      poses[node] = blended;
    }
  }
  return poses;
}

}  // namespace adaptive_lego_loam
