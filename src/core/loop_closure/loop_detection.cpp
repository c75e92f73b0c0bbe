#include "adaptive_lego_loam/core/loop_closure/loop_detection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/loop_closure/stepped_icp.h"
#include "adaptive_lego_loam/core/mapping/local_map.h"
#include "adaptive_lego_loam/core/mapping/scan_to_map.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {
namespace {

// A rigid transform needs three point pairs; fewer cannot be checked at all.
constexpr std::size_t kMinIcpPoints = 3;

std::size_t points_of(const Keyframe& keyframe) {
  return keyframe.has_clouds() ? keyframe.corners->size() + keyframe.surfaces->size() : 0;
}

// Its corners and surfaces placed by `pose`.
CloudPtr cloud_at(const Keyframe& keyframe, const Eigen::Isometry3d& pose) {
  CloudPtr cloud(new Cloud);
  if (!keyframe.has_clouds()) return cloud;
  cloud->reserve(points_of(keyframe));
  keyframe.corners->unpack(pose, *cloud);
  keyframe.surfaces->unpack(pose, *cloud);
  return cloud;
}

CloudPtr cloud_in_map(const Keyframe& keyframe) {
  return cloud_at(keyframe, keyframe.pose);
}

// The points of the current keyframe that verify a loop: those within verify_radius of it (the
// candidate's map holds that much around each keyframe), placed by `guess`.
CloudPtr verification_source(const Keyframe& keyframe, const Eigen::Isometry3d& guess,
                             const LoopClosureParams& params) {
  const CloudPtr sensor_frame = cloud_at(keyframe, Eigen::Isometry3d::Identity());
  const float squared_radius = static_cast<float>(params.verify_radius * params.verify_radius);
  Cloud near;
  near.reserve(sensor_frame->size());
  for (const CloudPoint& p : *sensor_frame) {
    if (p.getVector3fMap().squaredNorm() <= squared_radius) near.push_back(p);
  }
  return transform_cloud(near, guess);
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
std::size_t sample_step(std::size_t size, int most) {
  return std::max<std::size_t>((size + most - 1) / most, 1);
}

Cloud every_nth(const Cloud& cloud, std::size_t step) {
  Cloud sampled;
  sampled.reserve(cloud.size() / step + 1);
  for (std::size_t i = 0; i < cloud.size(); i += step)
    sampled.push_back(cloud[i]);
  return sampled;
}

CloudPtr sample(const CloudPtr& cloud, int most) {
  const std::size_t step = sample_step(cloud->size(), most);
  if (step == 1) return cloud;
  return CloudPtr(new Cloud(every_nth(*cloud, step)));
}

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
    case LoopStatus::kTooFewInliers:
      return "too few inliers";
    case LoopStatus::kBeyondDrift:
      return "beyond the drift bound";
  }
  return "unknown";
}

double path_between(const std::vector<Keyframe>& keyframes, int first, int last) {
  double driven = 0.0;
  for (int i = first + 1; i <= last; ++i)
    driven += (keyframes.at(i).pose.translation() - keyframes.at(i - 1).pose.translation()).norm();
  return driven;
}

bool far_enough_along(const std::vector<Keyframe>& keyframes, int candidate, int current,
                      const LoopClosureParams& params) {
  return path_between(keyframes, candidate, current) >= params.min_loop_path;
}

bool within_drift_bound(const std::vector<Keyframe>& keyframes, const LoopDetection& loop,
                        const LoopClosureParams& params) {
  const double driven = path_between(keyframes, loop.matched_index, loop.current_index);
  const Eigen::Isometry3d odometry =
      keyframes.at(loop.matched_index).pose.inverse() * keyframes.at(loop.current_index).pose;
  const double correction = (odometry.inverse() * loop.relative_pose).translation().norm();
  return correction <= params.max_drift_fraction * driven + params.max_drift_offset;
}

const char* to_string(CandidateSource source) {
  return source == CandidateSource::kPlace ? "place recognition" : "radius search";
}

std::optional<LoopCandidate> radius_candidate(const std::vector<Keyframe>& keyframes,
                                              int current_index, const LoopClosureParams& params) {
  const Keyframe& current = keyframes.at(current_index);
  const Eigen::Vector3d position = current.pose.translation();
  int nearest = -1;
  double nearest_distance = 0.0;
  for (int i = 0; i < static_cast<int>(keyframes.size()); ++i) {
    if (i == current_index || !keyframes[i].has_clouds() || keyframes[i].degenerate) continue;
    if (!old_enough(keyframes[i], current, params)) continue;
    const double distance = (keyframes[i].pose.translation() - position).norm();
    if (distance > params.search_radius) continue;
    if (nearest < 0 || distance < nearest_distance) {
      nearest = i;
      nearest_distance = distance;
    }
  }
  if (nearest < 0) return std::nullopt;
  LoopCandidate candidate;
  candidate.matched_index = nearest;
  candidate.source = CandidateSource::kRadius;
  candidate.guess = current.pose;
  return candidate;
}

struct LoopDetectionJob::Work {
  enum class Phase { kMap, kFilter, kTree, kIcp, kRefinementMap, kRefine };
  Phase phase = Phase::kMap;
  std::vector<Keyframe> map_keyframes;  // the candidate's neighbourhood, as when the job began
  std::size_t mapped = 0;               // how many of them are in the map
  std::optional<VoxelSums> map_sums;    // with voxel_size > 0
  CloudPtr map{new Cloud};  // the map to align to (gathered here directly without a filter)
  CloudPtr source;
  Eigen::Isometry3d guess, matched_pose;
  std::unique_ptr<SteppedIcp> icp;
  Keyframe current;  // as when the job began
  // Refining: the candidate's map as mapping's, where ICP put the keyframe, and the match (of the
  // keyframe's sampled points, kept here for it) from there.
  std::optional<LocalMap> refinement_map;
  Eigen::Isometry3d icp_pose;
  Cloud refinement_corners, refinement_surfaces;
  std::unique_ptr<SteppedMapMatch> refinement;
};

LoopDetectionJob::LoopDetectionJob(const std::vector<Keyframe>& keyframes, int current_index,
                                   const std::optional<LoopCandidate>& candidate,
                                   const LoopClosureParams& params,
                                   const std::optional<MappingParams>& refinement)
    : params_(params), refinement_(refinement) {
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
  if (candidate) {
    detection_.matched_index = candidate->matched_index;
    detection_.source = candidate->source;
    work_ = std::make_unique<Work>();
    if (params.voxel_size > 0.0) work_->map_sums.emplace(params.voxel_size);
    work_->map_keyframes =
        neighbourhood(keyframes, detection_.matched_index, current_index, params);
    work_->source = sample(verification_source(keyframes[current_index], candidate->guess, params),
                           params.icp_max_points);
    work_->current = keyframes[current_index];
    work_->guess = candidate->guess;
    work_->matched_pose = keyframes.at(detection_.matched_index).pose;
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
    case Work::Phase::kRefinementMap:
      add_to_refinement_map();
      break;
    case Work::Phase::kRefine:
      refine();
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
    // Growing the table as it fills would re-insert every voxel in one step; the neighbourhood's
    // keyframes overlap, about 4 points or more to a voxel.
    std::size_t total = 0;
    for (const Keyframe& keyframe : work.map_keyframes)
      total += points_of(keyframe);
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
  if (!refinement_) work_->map_keyframes.clear();
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
      conclude(icp);
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

void LoopDetectionJob::conclude(SteppedIcp& icp) {
  detection_.fitness = icp.fitness();
  const SteppedIcp::Inliers inliers = icp.inliers(params_.inlier_distance);
  detection_.inlier_ratio = inliers.ratio;
  detection_.inlier_mse = inliers.mean_squared_distance;
  // ICP moved the source from the guess: the current keyframe belongs there.
  const Eigen::Isometry3d corrected = isometry_of(icp.transformation()) * work_->guess;
  detection_.correction = corrected * work_->current.pose.inverse();
  if (inliers.ratio < params_.min_inlier_ratio ||
      inliers.mean_squared_distance > params_.max_inlier_mse) {
    finish(LoopStatus::kTooFewInliers);
    return;
  }
  if (!refinement_) {
    accept(corrected);
    return;
  }
  Work& work = *work_;
  work.icp_pose = corrected;
  work.mapped = 0;
  work.refinement_map.emplace(*refinement_);
  work.phase = Work::Phase::kRefinementMap;
}

// Places the candidate's keyframes into the refinement's map until map_points_per_scan points
// went in.
void LoopDetectionJob::add_to_refinement_map() {
  Work& work = *work_;
  work.icp.reset();
  work.map.reset();
  std::size_t points = 0;
  while (work.mapped < work.map_keyframes.size() &&
         points < static_cast<std::size_t>(params_.map_points_per_scan)) {
    const Keyframe& keyframe = work.map_keyframes[work.mapped++];
    if (!keyframe.has_clouds()) continue;  // merged into a neighbour
    work.refinement_map->add(keyframe);
    points += points_of(keyframe);
  }
  if (work.mapped == work.map_keyframes.size()) work.phase = Work::Phase::kRefine;
}

// The current keyframe's corners and surfaces, every n-th, at most icp_max_points in all, matched
// from ICP's pose, icp_iterations_per_scan iterations a step. All of them, not only those ICP
// aligned: the match leaves out points without a line or plane of the map near them, and what is
// farther adds to the constraints.
void LoopDetectionJob::refine() {
  Work& work = *work_;
  if (!work.refinement) {
    const CloudPtr corners = work.current.corners->unpack();
    const CloudPtr surfaces = work.current.surfaces->unpack();
    const std::size_t step =
        sample_step(corners->size() + surfaces->size(), params_.icp_max_points);
    work.refinement_corners = every_nth(*corners, step);
    work.refinement_surfaces = every_nth(*surfaces, step);
    work.refinement = std::make_unique<SteppedMapMatch>(*refinement_, work.refinement_corners,
                                                        work.refinement_surfaces,
                                                        *work.refinement_map, work.icp_pose);
  }
  for (int piece = 0; piece < params_.icp_iterations_per_scan && !work.refinement->done(); ++piece)
    work.refinement->iterate();
  if (!work.refinement->done()) return;
  const MapMatchResult match = work.refinement->result();
  if (!match.matched) {
    accept(work.icp_pose);
    return;
  }
  detection_.refinement_m = (match.pose.translation() - work.icp_pose.translation()).norm();
  accept(match.pose);
}

void LoopDetectionJob::accept(const Eigen::Isometry3d& corrected) {
  detection_.correction = corrected * work_->current.pose.inverse();
  detection_.relative_pose = work_->matched_pose.inverse() * corrected;
  finish(LoopStatus::kAccepted);
}

void LoopDetectionJob::finish(LoopStatus status) {
  detection_.status = status;
  work_.reset();
}

LoopDetection detect_loop(const std::vector<Keyframe>& keyframes, int current_index,
                          const std::optional<LoopCandidate>& candidate,
                          const LoopClosureParams& params,
                          const std::optional<MappingParams>& refinement) {
  LoopClosureParams unbounded = params;
  unbounded.map_points_per_scan = std::numeric_limits<int>::max();
  unbounded.icp_iterations_per_scan = std::numeric_limits<int>::max();
  LoopDetectionJob job(keyframes, current_index, candidate, unbounded, refinement);
  while (!job.step()) {
  }
  return job.detection();
}

LoopDetection detect_loop(const std::vector<Keyframe>& keyframes, int current_index,
                          const LoopClosureParams& params) {
  if (current_index < 0 || current_index >= static_cast<int>(keyframes.size())) {
    throw std::out_of_range("detect_loop: keyframe " + std::to_string(current_index) + " of " +
                            std::to_string(keyframes.size()));
  }
  return detect_loop(keyframes, current_index, radius_candidate(keyframes, current_index, params),
                     params);
}

}  // namespace adaptive_lego_loam
