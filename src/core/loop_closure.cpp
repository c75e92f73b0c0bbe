#include "adaptive_lego_loam/core/loop_closure.h"

#include <pcl/registration/icp.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/core/kdtree.h"
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

// The candidate and up to neighbourhood_keyframes keyframes on either side of it, leaving out
// the current one and any less than min_time_gap older.
std::vector<Keyframe> neighbourhood(const std::vector<Keyframe>& keyframes, int matched,
                                    int current, const LoopClosureParams& params) {
  const int first = std::max(0, matched - params.neighbourhood_keyframes);
  const int last =
      std::min(static_cast<int>(keyframes.size()) - 1, matched + params.neighbourhood_keyframes);
  std::vector<Keyframe> chosen;
  for (int i = first; i <= last; ++i) {
    if (i != current && old_enough(keyframes[i], keyframes[current], params)) {
      chosen.push_back(keyframes[i]);
    }
  }
  return chosen;
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

// PCL's KD-tree search answered by PointKdTree, which finds the same nearest points at the same
// squared distances (both sum dx^2 + dy^2 + dz^2 in float) in a third of the time and builds in
// half of it; only an exact tie may be broken differently. Serves ICP's correspondences and
// fitness, which only ask for the k nearest points of a point.
class PointKdTreeSearch : public pcl::search::KdTree<CloudPoint> {
 public:
  void setInputCloud(const PointCloudConstPtr& cloud,
                     const IndicesConstPtr& indices = IndicesConstPtr()) override {
    if (indices) throw std::invalid_argument("PointKdTreeSearch: indices are not supported");
    input_ = cloud;
    points_.build(cloud);
  }

  int nearestKSearch(const CloudPoint& point, int k, pcl::Indices& k_indices,
                     std::vector<float>& k_sqr_distances) const override {
    found_.resize(static_cast<std::size_t>(std::max(k, 0)));
    k_sqr_distances.resize(found_.size());
    const int count =
        points_.nearest(point.getVector3fMap(), k, found_.data(), k_sqr_distances.data());
    k_indices.assign(found_.begin(), found_.begin() + count);
    k_sqr_distances.resize(static_cast<std::size_t>(count));
    return count;
  }

  int radiusSearch(const CloudPoint&, double, pcl::Indices&, std::vector<float>&,
                   unsigned int) const override {
    throw std::logic_error("PointKdTreeSearch: radius search is not supported");
  }

 private:
  PointKdTree points_;
  mutable std::vector<uint32_t> found_;  // index buffer, kept to spare an allocation a query
};

// PCL's point-to-point ICP one iteration per iterate(), the same iterations as one align() would
// run, bit for bit: each call aligns the cloud the previous one left (align() from the identity,
// not the original cloud moved by the product of the steps, which rounds differently), and the
// convergence criteria, which keep the previous iteration's MSE, are told that the end of a
// call is no convergence (otherwise they skip their checks there).
class SteppedIcp : public pcl::IterativeClosestPoint<CloudPoint, CloudPoint> {
 public:
  using State = pcl::registration::DefaultConvergenceCriteria<float>::ConvergenceState;

  SteppedIcp(CloudPtr source, const CloudPtr& target, const LoopClosureParams& params)
      : source_(source), moved_(std::move(source)) {
    setMaxCorrespondenceDistance(params.icp_max_correspondence_distance);
    setMaximumIterations(1);
    setTransformationEpsilon(1e-6);
    setEuclideanFitnessEpsilon(1e-6);
    setRANSACIterations(0);
    getConvergeCriteria()->setFailureAfterMaximumIterations(true);
    // Built once here; forced, so that no align() builds it again.
    auto tree = std::make_shared<PointKdTreeSearch>();
    tree->setInputCloud(target);
    setSearchMethodTarget(tree, true);
    setInputTarget(target);
  }

  void iterate() {
    setInputSource(moved_);
    CloudPtr moved(new Cloud);
    align(*moved);
    moved_ = std::move(moved);
    transformation_so_far_ = getFinalTransformation() * transformation_so_far_;
    ++iterations_;
  }

  int iterations() const { return iterations_; }
  bool found_no_correspondences() const {
    return state() == State::CONVERGENCE_CRITERIA_NO_CORRESPONDENCES;
  }
  // Met a tolerance (translation, rotation or MSE change).
  bool converged() const {
    return state() == State::CONVERGENCE_CRITERIA_TRANSFORM ||
           state() == State::CONVERGENCE_CRITERIA_ABS_MSE ||
           state() == State::CONVERGENCE_CRITERIA_REL_MSE;
  }
  const Matrix4& transformation() const { return transformation_so_far_; }

  // PCL's fitness (mean squared distance of every source point to its nearest target point)
  // of the source moved by every iteration so far, as align() would leave it.
  double fitness() {
    setInputSource(source_);
    final_transformation_ = transformation_so_far_;
    return getFitnessScore();
  }

 private:
  State state() const { return convergence_criteria_->getConvergenceState(); }

  CloudPtr source_;  // as sampled
  CloudPtr moved_;   // as the last iteration left it
  Matrix4 transformation_so_far_ = Matrix4::Identity();
  int iterations_ = 0;
};

Eigen::Isometry3d isometry_of(const Eigen::Matrix4f& transformation) {
  const Eigen::Matrix4d t = transformation.cast<double>();
  Eigen::Isometry3d isometry = Eigen::Isometry3d::Identity();
  isometry.linear() = Eigen::Quaterniond(t.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  isometry.translation() = t.topRightCorner<3, 1>();
  return isometry;
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

struct LoopDetectionJob::Work {
  enum class Phase { kMap, kFilter, kTree, kIcp };
  Phase phase = Phase::kMap;
  std::vector<Keyframe> map_keyframes;  // the candidate's neighbourhood, as when the job began
  std::size_t mapped = 0;               // how many of them are in the map
  std::optional<VoxelSums> map_sums;    // with voxel_size > 0
  CloudPtr map{new Cloud};  // the map to align to (gathered here directly without a filter)
  CloudPtr source;
  Eigen::Isometry3d current_pose, matched_pose;
  std::unique_ptr<SteppedIcp> icp;
};

LoopDetectionJob::LoopDetectionJob(const std::vector<Keyframe>& keyframes, int current_index,
                                   const LoopClosureParams& params)
    : params_(params) {
  if (current_index < 0 || current_index >= static_cast<int>(keyframes.size())) {
    throw std::out_of_range("detect_loop: keyframe " + std::to_string(current_index) + " of " +
                            std::to_string(keyframes.size()));
  }
  const Stopwatch stopwatch;
  detection_.current_index = current_index;
  if (!params.enabled) {
    detection_.status = LoopStatus::kDisabled;
    return;
  }
  detection_.matched_index = find_loop_candidate(keyframes, current_index, params);
  if (detection_.matched_index >= 0) {
    work_ = std::make_unique<Work>();
    if (params.voxel_size > 0.0) work_->map_sums.emplace(params.voxel_size);
    work_->map_keyframes =
        neighbourhood(keyframes, detection_.matched_index, current_index, params);
    work_->source = sample(cloud_in_map(keyframes[current_index]), params.icp_max_points);
    work_->current_pose = keyframes[current_index].pose;
    work_->matched_pose = keyframes[detection_.matched_index].pose;
    if (work_->source->size() < kMinIcpPoints) finish(LoopStatus::kTooFewPoints);
  } else {
    finish(LoopStatus::kNoCandidate);
  }
  detection_.time_ms = stopwatch.elapsed_ms();
}

LoopDetectionJob::~LoopDetectionJob() = default;
LoopDetectionJob::LoopDetectionJob(LoopDetectionJob&&) noexcept = default;
LoopDetectionJob& LoopDetectionJob::operator=(LoopDetectionJob&&) noexcept = default;

bool LoopDetectionJob::done() const {
  return !work_;
}

bool LoopDetectionJob::step() {
  if (done()) return true;
  const Stopwatch stopwatch;
  switch (work_->phase) {
    case Work::Phase::kMap:
      add_to_map();
      break;
    case Work::Phase::kFilter:
      filter_map();
      break;
    case Work::Phase::kTree:
      prepare_icp();
      break;
    case Work::Phase::kIcp:
      iterate_icp();
      break;
  }
  detection_.time_ms += stopwatch.elapsed_ms();
  return done();
}

// Places keyframes into the map until map_points_per_scan points went in. A voxel filter of the
// keyframes added one by one equals that of their concatenation.
void LoopDetectionJob::add_to_map() {
  Work& work = *work_;
  if (work.mapped == 0 && work.map_sums) {
    // Growing the table as it fills would re-insert every voxel in one step (6-7 ms on a VLP-16
    // loop); the neighbourhood's keyframes overlap, about 4 points or more to a voxel.
    std::size_t total = 0;
    for (const Keyframe& keyframe : work.map_keyframes) {
      for (const CloudPtr& cloud : {keyframe.corners, keyframe.surfaces, keyframe.outliers})
        total += cloud ? cloud->size() : 0;
    }
    work.map_sums->reserve(total / 4);
  }
  std::size_t points = 0;
  while (work.mapped < work.map_keyframes.size() &&
         points < static_cast<std::size_t>(params_.map_points_per_scan)) {
    const CloudPtr placed = cloud_in_map(work.map_keyframes[work.mapped++]);
    points += placed->size();
    if (work.map_sums) {
      work.map_sums->add(*placed);
    } else {
      *work.map += *placed;
    }
  }
  if (work.mapped == work.map_keyframes.size()) work.phase = Work::Phase::kFilter;
}

// The voxel filter's centroids: a walk over its whole table, a step of its own.
void LoopDetectionJob::filter_map() {
  if (work_->map_sums) {
    work_->map = work_->map_sums->centroids();
    work_->map_sums.reset();
  }
  work_->map_keyframes.clear();
  if (work_->map->size() < kMinIcpPoints) {
    finish(LoopStatus::kTooFewPoints);
    return;
  }
  work_->phase = Work::Phase::kTree;
}

void LoopDetectionJob::prepare_icp() {
  work_->icp = std::make_unique<SteppedIcp>(work_->source, work_->map, params_);
  work_->phase = Work::Phase::kIcp;
}

// Runs up to icp_iterations_per_scan iterations; the fitness, once ICP has converged or run
// icp_max_iterations (which counts as converged, as PCL's hasConverged() has it), takes the place
// of one.
void LoopDetectionJob::iterate_icp() {
  SteppedIcp& icp = *work_->icp;
  for (int piece = 0; piece < params_.icp_iterations_per_scan; ++piece) {
    if (icp.converged() || icp.iterations() >= params_.icp_max_iterations) {
      conclude(icp.fitness(), icp.transformation());
      return;
    }
    icp.iterate();
    detection_.icp_iterations = icp.iterations();
    if (icp.found_no_correspondences()) {
      finish(LoopStatus::kNotConverged);
      return;
    }
  }
}

void LoopDetectionJob::conclude(double fitness, const Eigen::Matrix4f& transformation) {
  detection_.fitness = fitness;
  detection_.correction = isometry_of(transformation);
  if (fitness >= params_.fitness_threshold) {
    finish(LoopStatus::kPoorFitness);
    return;
  }
  const Eigen::Isometry3d corrected = detection_.correction * work_->current_pose;
  detection_.relative_pose = work_->matched_pose.inverse() * corrected;
  finish(LoopStatus::kAccepted);
}

void LoopDetectionJob::finish(LoopStatus status) {
  detection_.status = status;
  work_.reset();
}

LoopDetection detect_loop(const std::vector<Keyframe>& keyframes, int current_index,
                          const LoopClosureParams& params) {
  LoopClosureParams unbounded = params;
  unbounded.map_points_per_scan = std::numeric_limits<int>::max();
  unbounded.icp_iterations_per_scan = std::numeric_limits<int>::max();
  LoopDetectionJob job(keyframes, current_index, unbounded);
  while (!job.step()) {
  }
  return job.detection();
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

void KeyframeGraph::set_poses(const std::vector<Keyframe>& keyframes) {
  if (static_cast<int>(keyframes.size()) != graph_.node_count()) {
    throw std::invalid_argument("KeyframeGraph: " + std::to_string(keyframes.size()) +
                                " keyframes for " + std::to_string(graph_.node_count()) + " nodes");
  }
  for (int i = 0; i < graph_.node_count(); ++i)
    graph_.set_pose(i, keyframes[i].pose);
}

LoopOptimization::LoopOptimization(const KeyframeGraph& graph, const LoopDetection& loop,
                                   const LoopClosureParams& params)
    : loop_(loop),
      with_loop_(graph),
      iterations_per_step_(params.graph_iterations_per_scan),
      max_iterations_(graph.graph().options().max_iterations) {
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
  graph.add_loop(loop_);
  graph.set_poses(keyframes);
  return motion;
}

}  // namespace adaptive_lego_loam
