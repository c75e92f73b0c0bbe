#include "adaptive_lego_loam/core/loop_closure/keyframe_graph.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam {

KeyframeGraph::KeyframeGraph(const LoopClosureParams& params)
    : odometry_information_(information_from_sigmas(
          params.odometry_sigma_translation, params.odometry_sigma_rotation_deg * M_PI / 180.0)),
      loop_information_(information_from_sigmas(params.loop_sigma_translation,
                                                params.loop_sigma_rotation_deg * M_PI / 180.0)),
      graph_([&] {
        PoseGraphOptions options;
        options.loop_loss = params.robust_loss;
        options.loop_loss_scale = params.robust_loss_scale;
        return options;
      }()) {}

void KeyframeGraph::add_keyframe(const Keyframe& keyframe) {
  if (keyframe.index != graph_.node_count()) {
    throw std::invalid_argument("KeyframeGraph: keyframe " + std::to_string(keyframe.index) +
                                " added, expected " + std::to_string(graph_.node_count()));
  }
  const int node = graph_.add_node(keyframe.pose);
  if (node == 0) return;
  PoseGraphEdge edge;
  edge.from = node - 1;
  edge.to = node;
  edge.measurement = graph_.pose(node - 1).inverse() * keyframe.pose;
  edge.information = odometry_information_;
  edge.kind = EdgeKind::kOdometry;
  graph_.add_edge(edge);
}

void KeyframeGraph::add_loop(const LoopDetection& loop) {
  if (!loop.accepted()) {
    throw std::invalid_argument(std::string("KeyframeGraph: loop not accepted (") +
                                to_string(loop.status) + ")");
  }
  PoseGraphEdge edge;
  edge.from = loop.matched_index;
  edge.to = loop.current_index;
  edge.measurement = loop.relative_pose;
  edge.information = loop_information_;
  edge.kind = EdgeKind::kLoop;
  graph_.add_edge(edge);
}

PoseGraphSummary KeyframeGraph::optimize(std::vector<Keyframe>& keyframes) {
  if (static_cast<int>(keyframes.size()) != graph_.node_count()) {
    throw std::invalid_argument("KeyframeGraph: " + std::to_string(keyframes.size()) +
                                " keyframes for " + std::to_string(graph_.node_count()) + " nodes");
  }
  const PoseGraphSummary summary = graph_.optimize();
  for (int i = 0; i < graph_.node_count(); ++i)
    keyframes[i].pose = graph_.pose(i);
  return summary;
}

void KeyframeGraph::set_poses(const std::vector<Keyframe>& keyframes) {
  if (static_cast<int>(keyframes.size()) != graph_.node_count()) {
    throw std::invalid_argument("KeyframeGraph: " + std::to_string(keyframes.size()) +
                                " keyframes for " + std::to_string(graph_.node_count()) + " nodes");
  }
  for (int i = 0; i < graph_.node_count(); ++i)
    graph_.set_pose(i, keyframes[i].pose);
}

int KeyframeGraph::remove_loops_off_by(double sigmas) {
  int removed = 0;
  for (int edge = static_cast<int>(graph_.edges().size()) - 1; edge >= 0; --edge) {
    if (graph_.edges()[edge].kind != EdgeKind::kLoop) continue;
    if (graph_.residual_norm(edge) <= sigmas) continue;
    graph_.remove_edge(edge);
    ++removed;
  }
  return removed;
}

int KeyframeGraph::loops() const {
  int count = 0;
  for (const PoseGraphEdge& edge : graph_.edges())
    count += edge.kind == EdgeKind::kLoop;
  return count;
}

LoopOptimization::LoopOptimization(const KeyframeGraph& graph,
                                   const std::vector<LoopDetection>& loops,
                                   const LoopClosureParams& params)
    : loops_(loops),
      with_loop_(graph),
      iterations_per_step_(params.graph_iterations_per_scan),
      max_iterations_(graph.graph().options().max_iterations) {
  for (const LoopDetection& loop : loops)
    with_loop_.add_loop(loop);
  optimized_ = reduce_graph(with_loop_.graph(), params.graph_max_nodes);
}

bool LoopOptimization::step() {
  if (done_) return true;
  const int iterations = std::min(iterations_per_step_, max_iterations_ - iterations_);
  const PoseGraphSummary summary = optimized_.graph.optimize(iterations, trust_region_radius_);
  iterations_ += iterations;
  trust_region_radius_ = summary.trust_region_radius;
  done_ = summary.converged || iterations_ >= max_iterations_;
  return done_;
}

Eigen::Isometry3d LoopOptimization::apply(KeyframeGraph& graph,
                                          std::vector<Keyframe>& keyframes) const {
  if (!done_) throw std::logic_error("LoopOptimization: applied before it finished");
  const std::vector<Eigen::Isometry3d> optimized = expand_poses(optimized_, with_loop_.graph());
  const int covered = static_cast<int>(optimized.size());
  if (static_cast<int>(keyframes.size()) < covered ||
      graph.graph().node_count() != static_cast<int>(keyframes.size())) {
    throw std::invalid_argument("LoopOptimization: keyframes do not extend the optimised graph");
  }
  const Eigen::Isometry3d last_before = keyframes[covered - 1].pose;
  for (int i = 0; i < covered; ++i)
    keyframes[i].pose = optimized[i];
  const Eigen::Isometry3d motion = keyframes[covered - 1].pose * last_before.inverse();
  for (std::size_t i = covered; i < keyframes.size(); ++i)
    keyframes[i].pose = motion * keyframes[i].pose;
  for (const LoopDetection& loop : loops_)
    graph.add_loop(loop);
  graph.set_poses(keyframes);
  return motion;
}

}  // namespace adaptive_lego_loam
