#include "adaptive_lego_loam/core/loop_closure.h"

#include <pcl/registration/icp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/core/timing.h"
#include "adaptive_lego_loam/core/voxel_filter.h"

namespace adaptive_lego_loam {
namespace {

// A rigid transform needs three point pairs; fewer cannot be checked at all.
constexpr std::size_t kMinIcpPoints = 3;

void append(Cloud& into, const CloudPtr& cloud) {
  if (cloud) into += *cloud;
}

CloudPtr cloud_in_map(const Keyframe& keyframe) {
  Cloud sensor_frame;
  append(sensor_frame, keyframe.corners);
  append(sensor_frame, keyframe.surfaces);
  append(sensor_frame, keyframe.outliers);
  return transform_cloud(sensor_frame, keyframe.pose);
}

bool old_enough(const Keyframe& candidate, const Keyframe& current,
                const LoopClosureParams& params) {
  return candidate.stamp <= current.stamp - params.min_time_gap;
}

CloudPtr neighbourhood_map(const std::vector<Keyframe>& keyframes, int matched, int current,
                           const LoopClosureParams& params) {
  const int first = std::max(0, matched - params.neighbourhood_keyframes);
  const int last =
      std::min(static_cast<int>(keyframes.size()) - 1, matched + params.neighbourhood_keyframes);
  CloudPtr map(new Cloud);
  for (int i = first; i <= last; ++i) {
    if (i == current || !old_enough(keyframes[i], keyframes[current], params)) continue;
    *map += *cloud_in_map(keyframes[i]);
  }
  return voxel_filter(*map, params.voxel_size);
}

// Every n-th point of `cloud`, at most `most` of them. ICP's time grows with its source; a
// uniform sample keeps the fitness (a mean over the source) comparable, where a voxel filter's
// centroids would raise it.
CloudPtr sample(const CloudPtr& cloud, int most) {
  const std::size_t step = (cloud->size() + most - 1) / most;
  if (step <= 1) return cloud;
  CloudPtr sampled(new Cloud);
  sampled->reserve(cloud->size() / step + 1);
  for (std::size_t i = 0; i < cloud->size(); i += step)
    sampled->push_back((*cloud)[i]);
  return sampled;
}

// Runs ICP of `source` onto `target` and fills status, fitness and correction.
void align(const CloudPtr& source, const CloudPtr& target, const LoopClosureParams& params,
           LoopDetection& loop) {
  pcl::IterativeClosestPoint<CloudPoint, CloudPoint> icp;
  icp.setMaxCorrespondenceDistance(params.icp_max_correspondence_distance);
  icp.setMaximumIterations(params.icp_max_iterations);
  icp.setTransformationEpsilon(1e-6);
  icp.setEuclideanFitnessEpsilon(1e-6);
  icp.setRANSACIterations(0);
  icp.setInputSource(source);
  icp.setInputTarget(target);
  Cloud aligned;
  icp.align(aligned);
  if (!icp.hasConverged()) {
    loop.status = LoopStatus::kNotConverged;
    return;
  }
  loop.fitness = icp.getFitnessScore();
  const Eigen::Matrix4d correction = icp.getFinalTransformation().cast<double>();
  loop.correction.linear() =
      Eigen::Quaterniond(correction.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  loop.correction.translation() = correction.topRightCorner<3, 1>();
  loop.status =
      loop.fitness < params.fitness_threshold ? LoopStatus::kAccepted : LoopStatus::kPoorFitness;
}

}  // namespace

const char* to_string(LoopStatus status) {
  switch (status) {
    case LoopStatus::kAccepted:
      return "accepted";
    case LoopStatus::kDisabled:
      return "disabled";
    case LoopStatus::kNoCandidate:
      return "no candidate";
    case LoopStatus::kTooFewPoints:
      return "too few points";
    case LoopStatus::kNotConverged:
      return "ICP did not converge";
    case LoopStatus::kPoorFitness:
      return "ICP fitness too high";
  }
  return "unknown";
}

int find_loop_candidate(const std::vector<Keyframe>& keyframes, int current_index,
                        const LoopClosureParams& params) {
  const Keyframe& current = keyframes.at(current_index);
  const Eigen::Vector3d position = current.pose.translation();
  int nearest = -1;
  double nearest_distance = 0.0;
  for (int i = 0; i < static_cast<int>(keyframes.size()); ++i) {
    if (i == current_index || !old_enough(keyframes[i], current, params)) continue;
    const double distance = (keyframes[i].pose.translation() - position).norm();
    if (distance > params.search_radius) continue;
    if (nearest < 0 || distance < nearest_distance) {
      nearest = i;
      nearest_distance = distance;
    }
  }
  return nearest;
}

LoopDetection detect_loop(const std::vector<Keyframe>& keyframes, int current_index,
                          const LoopClosureParams& params) {
  if (current_index < 0 || current_index >= static_cast<int>(keyframes.size())) {
    throw std::out_of_range("detect_loop: keyframe " + std::to_string(current_index) + " of " +
                            std::to_string(keyframes.size()));
  }
  const Stopwatch stopwatch;
  LoopDetection loop;
  loop.current_index = current_index;
  if (!params.enabled) {
    loop.status = LoopStatus::kDisabled;
    return loop;
  }
  loop.matched_index = find_loop_candidate(keyframes, current_index, params);
  if (loop.matched_index < 0) {
    loop.status = LoopStatus::kNoCandidate;
    loop.time_ms = stopwatch.elapsed_ms();
    return loop;
  }
  const CloudPtr source = sample(cloud_in_map(keyframes[current_index]), params.icp_max_points);
  const CloudPtr target = neighbourhood_map(keyframes, loop.matched_index, current_index, params);
  if (source->size() < kMinIcpPoints || target->size() < kMinIcpPoints) {
    loop.status = LoopStatus::kTooFewPoints;
  } else {
    align(source, target, params, loop);
  }
  if (loop.accepted()) {
    const Eigen::Isometry3d corrected = loop.correction * keyframes[current_index].pose;
    loop.relative_pose = keyframes[loop.matched_index].pose.inverse() * corrected;
  }
  loop.time_ms = stopwatch.elapsed_ms();
  return loop;
}

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

}  // namespace adaptive_lego_loam
