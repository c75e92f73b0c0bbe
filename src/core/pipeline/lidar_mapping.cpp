#include "adaptive_lego_loam/core/pipeline/lidar_mapping.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_lego_loam/core/mapping/vertical_structure.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {

namespace {
constexpr double kLoopAttemptPeriod = 1.0;  // s

// Localization leaves the saved map as it is: no loop closes, nothing merges. This drive's own
// keyframes lag as in mapping: matched too soon, a 16-beam scan inherits their drift.
Config localization_config(Config config) {
  config.loop_closure.enabled = false;
  config.mapping.keyframe_merge_group = 1;
  return config;
}

// `pose` with its motion from `previous` along `direction` (previous' frame) as `predicted`'s.
Eigen::Isometry3d pose_held_along(const Eigen::Isometry3d& previous,
                                  const Eigen::Isometry3d& predicted, const Eigen::Isometry3d& pose,
                                  const Eigen::Vector3d& direction) {
  Eigen::Isometry3d motion = previous.inverse() * pose;
  const Eigen::Vector3d predicted_step = (previous.inverse() * predicted).translation();
  motion.translation() = held_along(motion.translation(), predicted_step, direction);
  Eigen::Isometry3d held = previous * motion;
  held.linear() = Eigen::Quaterniond(held.linear()).normalized().toRotationMatrix();
  return held;
}

}  // namespace

LidarMapping::LidarMapping(const Config& config)
    : params_(config.mapping),
      loop_params_(config.loop_closure),
      first_sweep_distorted_(!config.sensor.deskewed),
      graph_(config.loop_closure),
      places_(config.loop_closure),
      local_map_(config.mapping),
      merger_(config.mapping),
      matcher_(config.mapping) {}

LidarMapping::LidarMapping(const Config& config, std::vector<Keyframe> map,
                           const Eigen::Isometry3d& start)
    : LidarMapping(localization_config(config)) {
  if (map.empty()) throw std::invalid_argument("localization: the map has no keyframes");
  if (!config.mapping.enabled) {
    throw std::invalid_argument(config.source +
                                ": mapping.enabled is false: localization needs scan-to-map");
  }
  for (int i = 0; i < static_cast<int>(map.size()); ++i) {
    if (map[i].index != i) {
      throw std::invalid_argument("localization: map keyframe " + std::to_string(i) +
                                  " has index " + std::to_string(map[i].index));
    }
  }
  keyframes_ = std::move(map);
  localization_params_ = config.localization;
  localization_.emplace(config.localization, config.loop_closure,
                        static_cast<int>(keyframes_.size()));
  pose_ = start;
}

void LidarMapping::relocalize(const Eigen::Isometry3d& pose) {
  if (!localization_) return;
  pose_ = pose;
  localization_->restart();
  retire_recent_keyframes(0);
}

void LidarMapping::retire_recent_keyframes(int keep) {
  const int first_own = localization_->map_keyframes();
  for (int i = static_cast<int>(keyframes_.size()) - 1 - keep; i >= first_own; --i) {
    if (!keyframes_[i].has_clouds()) break;  // older ones were retired before
    keyframes_[i].corners.reset();
    keyframes_[i].surfaces.reset();
  }
}

// The drive's retired keyframes go, but for the newest local_map_lag_keyframes + 1 positions of the
// list (the local map's choice starts below them, and needs_keyframe() looks at the newest): what
// localization holds stays the same over hours, and the local map chooses the same keyframes as it
// would with them kept.
void LidarMapping::drop_retired_keyframes() {
  const int first_own = localization_->map_keyframes();
  const int size = static_cast<int>(keyframes_.size());
  const int kept_newest = std::min(params_.local_map_lag_keyframes, size - 1) + 1;
  int retired = 0;
  while (first_own + retired < size - kept_newest && !keyframes_[first_own + retired].has_clouds())
    ++retired;
  if (retired == 0) return;
  keyframes_.erase(keyframes_.begin() + first_own, keyframes_.begin() + first_own + retired);
  for (int i = first_own; i < static_cast<int>(keyframes_.size()); ++i)
    keyframes_[i].index = i;
  local_map_.keyframes_removed(first_own, retired);
}

void LidarMapping::start_loop_closure(double stamp) {
  const int newest = static_cast<int>(keyframes_.size()) - 1;
  if (keyframes_[newest].degenerate) return;
  // The candidate search is cheap and runs at every keyframe; the rest at most once a period.
  auto loop_worthy = [this, newest](const std::optional<LoopCandidate>& candidate) {
    return candidate &&
           far_enough_along(keyframes_, candidate->matched_index, newest, loop_params_);
  };
  std::optional<LoopCandidate> candidate = places_.candidate(keyframes_, newest);
  if (!loop_worthy(candidate)) candidate = radius_candidate(keyframes_, newest, loop_params_);
  if (!loop_worthy(candidate)) return;
  if (stamp - last_loop_attempt_ < kLoopAttemptPeriod) return;
  if (stamp - last_closure_ < loop_params_.min_closure_interval) return;
  last_loop_attempt_ = stamp;
  ++(candidate->source == CandidateSource::kPlace ? counts_.place_candidates
                                                  : counts_.radius_candidates);
  loop_job_.emplace(keyframes_, newest, candidate, loop_params_,
                    loop_params_.refine ? std::optional<MappingParams>(params_) : std::nullopt);
}

std::optional<LoopDetection> LidarMapping::advance_loop_closure(double stamp, bool new_keyframe) {
  if (!loop_params_.enabled) return std::nullopt;
  if (new_keyframe && !loop_closure_running()) start_loop_closure(stamp);
  if (loop_job_) {
    if (!loop_job_->step()) return std::nullopt;
    LoopDetection detection = loop_job_->detection();
    loop_job_.reset();
    if (!detection.accepted()) {
      ++counts_.rejected;
    } else if (!within_drift_bound(keyframes_, detection, loop_params_)) {
      ++counts_.beyond_drift;
      detection.status = LoopStatus::kBeyondDrift;
    } else {
      ++counts_.verified;
      confirm(detection);
    }
    return detection;
  }
  if (loop_optimization_ && loop_optimization_->step()) close_loop();
  return std::nullopt;
}

// A loop enters the pose graph with a second verified loop that agrees with it: both sides'
// poses and the two relative poses form a cycle, which must close within the consistency
// tolerances.
bool LidarMapping::loops_agree(const LoopDetection& first, const LoopDetection& second) const {
  const auto pose = [&](int index) { return keyframes_.at(index).pose; };
  const Eigen::Isometry3d current_side =
      pose(first.current_index).inverse() * pose(second.current_index);
  const Eigen::Isometry3d matched_side =
      pose(first.matched_index).inverse() * pose(second.matched_index);
  const Eigen::Isometry3d predicted = matched_side.inverse() * first.relative_pose * current_side;
  const Eigen::Isometry3d error = predicted.inverse() * second.relative_pose;
  return error.translation().norm() <= loop_params_.consistency_translation &&
         Eigen::AngleAxisd(error.rotation()).angle() <=
             loop_params_.consistency_rotation_deg * M_PI / 180.0;
}

void LidarMapping::confirm(const LoopDetection& loop) {
  const auto expired = [&](const LoopDetection& waiting) {
    return loop.current_index - waiting.current_index > loop_params_.consistency_window;
  };
  counts_.unconfirmed += static_cast<int>(std::count_if(pending_.begin(), pending_.end(), expired));
  pending_.erase(std::remove_if(pending_.begin(), pending_.end(), expired), pending_.end());
  for (auto waiting = pending_.begin(); waiting != pending_.end(); ++waiting) {
    if (!loops_agree(*waiting, loop)) continue;
    // The pose graph's first step waits for the next scan.
    loop_optimization_.emplace(graph_, std::vector<LoopDetection>{*waiting, loop}, loop_params_);
    pending_.erase(waiting);
    return;
  }
  pending_.push_back(loop);
}

void LidarMapping::close_loop() {
  const Eigen::Isometry3d motion = loop_optimization_->apply(graph_, keyframes_);
  counts_.closed += static_cast<int>(loop_optimization_->loops().size());
  closed_on_this_scan_ = !loop_optimization_->loops().empty();
  if (closed_on_this_scan_) last_closure_ = last_stamp_;
  loop_optimization_.reset();
  // The running pose moves with the newest keyframe; the local map is placed again from the
  // corrected keyframes.
  pose_ = motion * pose_;
  local_map_.keyframes_moved(motion);
  // A loop the optimised graph still cannot meet was wrong: out, and the graph solved without it.
  const int removed = graph_.remove_loops_off_by(loop_params_.max_loop_residual);
  if (removed > 0) {
    counts_.removed += removed;
    loop_optimization_.emplace(graph_, std::vector<LoopDetection>{}, loop_params_);
  }
}

std::optional<LoopDetection> LidarMapping::finish_loop_closure() {
  std::optional<LoopDetection> finished;
  while (loop_closure_running()) {
    if (std::optional<LoopDetection> detection = advance_loop_closure(last_stamp_, false)) {
      finished = detection;
    }
  }
  return finished;
}

bool LidarMapping::motion_is_plausible(const Eigen::Isometry3d& motion) const {
  if (!last_mapped_motion_) return true;
  const Eigen::Isometry3d change = last_mapped_motion_->inverse() * motion;
  const bool translation_ok =
      params_.max_motion_change <= 0.0 || change.translation().norm() <= params_.max_motion_change;
  const bool rotation_ok =
      params_.max_motion_change_deg <= 0.0 ||
      Eigen::AngleAxisd(change.linear()).angle() <= params_.max_motion_change_deg * M_PI / 180.0;
  return translation_ok && rotation_ok;
}

bool LidarMapping::gate_motion(const Eigen::Isometry3d& motion) {
  const bool released = params_.max_gated_scans > 0 && gated_in_a_row_ >= params_.max_gated_scans;
  const bool gated = !released && !motion_is_plausible(motion);
  gated_in_a_row_ = gated ? gated_in_a_row_ + 1 : 0;
  return gated;
}

bool LidarMapping::needs_keyframe() const {
  // The first keyframe of this drive (a saved map's keyframes are not its own).
  const int own_first = localization_ ? localization_->map_keyframes() : 0;
  if (static_cast<int>(keyframes_.size()) <= own_first) return true;
  const Eigen::Isometry3d since = keyframes_.back().pose.inverse() * pose_;
  return since.translation().norm() >= params_.keyframe_distance ||
         Eigen::AngleAxisd(since.linear()).angle() >= params_.keyframe_angle_deg * M_PI / 180.0;
}

Keyframe LidarMapping::make_keyframe(const FeatureSet& features, double stamp,
                                     const Eigen::Isometry3d& pose, bool degenerate) {
  Keyframe keyframe;
  keyframe.index = static_cast<int>(keyframes_.size());
  keyframe.frame = scans_;
  keyframe.stamp = stamp;
  keyframe.pose = pose;
  keyframe.degenerate = degenerate;
  keyframe.corners = pack(*keyframe_filter_(*features.less_sharp, params_.corner_voxel));
  keyframe.surfaces =
      pack(*keyframe_filter_(*features.less_flat, *features.outliers, params_.surface_voxel));
  return keyframe;
}

void LidarMapping::add_keyframe(const FeatureSet& features, double stamp, bool degenerate) {
  Keyframe keyframe = make_keyframe(features, stamp, pose_, degenerate);
  if (localization_) {
    keyframes_.push_back(std::move(keyframe));
    retire_recent_keyframes(localization_params_.recent_keyframes);
    drop_retired_keyframes();
    return;
  }
  if (loop_params_.enabled && loop_params_.place.enabled && !degenerate) {
    places_.add(keyframe.index, stamp,
                places_.describe(
                    {features.less_sharp.get(), features.less_flat.get(), features.outliers.get()},
                    keyframe.pose));
  }
  graph_.add_keyframe(keyframe);
  keyframes_.push_back(std::move(keyframe));
  std::vector<std::pair<int, int>> revisits;
  merger_.merge_old(keyframes_, &revisits);
  for (const auto& [first, last] : revisits)
    places_.forget(first, last);
}

SensorPriors LidarMapping::sensor_priors(const MotionPrediction* sensors,
                                         const std::optional<SceneDegeneration>& scene) const {
  SensorPriors priors;
  if (!sensors || scans_ == 0) return priors;
  priors.previous = pose_;
  priors.motion = sensors->motion;
  priors.scene = scene;
  if (const std::optional<Eigen::Vector3d> up = map_gravity_.up(); up && sensors->gravity) {
    priors.gravity = sensors->gravity;
    priors.map_up = *up;
  }
  return priors;
}

void LidarMapping::process(const FeatureSet& features, const Eigen::Isometry3d& odometry_pose,
                           double stamp, const std::optional<WeakDirectionPrior>& prior,
                           MappingOutput& out, const MotionPrediction* sensors,
                           const std::optional<SceneDegeneration>& scene,
                           const std::optional<Eigen::Vector3d>& odometry_held) {
  Stopwatch watch;
  out.times.clear();
  const Eigen::Isometry3d motion = last_odometry_pose_
                                       ? last_odometry_pose_->inverse() * odometry_pose
                                       : Eigen::Isometry3d::Identity();
  last_odometry_pose_ = odometry_pose;
  // A large object moving along with the sensor (a truck overtaking) can drag the scan-to-scan
  // estimate; scan-to-map then starts from the previous velocity instead.
  out.motion_gated = gate_motion(motion);
  Eigen::Isometry3d pose = pose_ * (out.motion_gated ? *last_mapped_motion_ : motion);
  // Without a solve after it (mapping off, or no map yet), a gated scan's pose comes from a
  // velocity taken from the pose itself by an inverse that assumes a rotation: the rounding would
  // grow scan after scan.
  pose.linear() = Eigen::Quaterniond(pose.linear()).normalized().toRotationMatrix();
  const Eigen::Isometry3d previous_pose = pose_;
  const Eigen::Isometry3d predicted_pose = pose;
  out.match = MapMatchResult();
  out.match.pose = pose;
  out.localization.reset();
  bool may_be_keyframe = true;

  if (params_.enabled && !keyframes_.empty()) {
    local_map_.update(keyframes_, pose.translation());
    out.times.add("local_map", watch.lap_ms());
    const CloudPtr corners = scan_filter_(*features.less_sharp, params_.scan_corner_voxel);
    const CloudPtr surfaces =
        scan_filter_(*features.less_flat, *features.outliers, params_.scan_surface_voxel);
    if (params_.vertical_prior_weight > 0.0) {
      wall_normals_ =
          wall_normals(*features.less_flat, pose.linear(), params_.vertical_prior_max_tilt_deg);
    }
    const SensorPriors priors = sensor_priors(sensors, scene);
    if (localization_) {
      may_be_keyframe = localize(features, *corners, *surfaces, stamp, prior, priors, pose, out);
    } else {
      out.match =
          matcher_.match(*corners, *surfaces, local_map_, pose, prior, wall_normals_, priors);
      pose = out.match.pose;
    }
    out.times.add("mapping", watch.lap_ms());
  }
  const bool aligned =
      out.localization && out.localization->alignment && out.localization->alignment->accepted();
  if (odometry_held && !aligned) {
    // Where the odometry found the scan blind, the map's rings pull toward standing still too.
    pose = pose_held_along(previous_pose, predicted_pose, pose, *odometry_held);
    out.match.information =
        discounted_along(out.match.information,
                         pose.linear().transpose() * previous_pose.linear() * *odometry_held, 0.0);
    out.match.odometry_held = true;
  }
  pose_ = pose;
  if (sensors && sensors->gravity) map_gravity_.add(pose_.linear(), *sensors->gravity);
  // The velocity exists once two scans have been mapped (an alignment's jump is not motion).
  if (scans_ >= 1) last_mapped_motion_ = aligned ? motion : previous_pose.inverse() * pose_;
  fusion_.update_mapping(odometry_pose, pose_);
  out.pose = pose_;
  out.motion = last_mapped_motion_;
  out.keyframe = may_be_keyframe && !(scans_ == 0 && first_sweep_distorted_) && needs_keyframe();
  if (out.keyframe) {
    add_keyframe(features, stamp, out.match.degenerate_directions > 0);
    out.times.add("keyframes", watch.lap_ms());
  }
  last_stamp_ = stamp;
  const bool loop_work = out.keyframe || loop_closure_running();
  closed_on_this_scan_ = false;
  out.loop = advance_loop_closure(stamp, out.keyframe);
  out.loop_closed = closed_on_this_scan_;
  if (loop_work) out.times.add("loop_closure", watch.lap_ms());
  if (out.loop_closed) {
    out.pose = pose_;
    fusion_.update_mapping(odometry_pose, pose_);
  }
  if (keeps_trajectory_) {
    // No keyframe yet, or localization (its own keyframes go, the map's never move): the pose.
    if (keyframes_.empty() || localization_) {
      anchors_.emplace_back(-1, pose_);
    } else {
      const Keyframe& anchor = keyframes_.back();
      anchors_.emplace_back(anchor.index, anchor.pose.inverse() * pose_);
    }
  }
  ++scans_;
  out.times.add("keyframes", watch.lap_ms());
}

bool LidarMapping::localize(const FeatureSet& features, const Cloud& corners, const Cloud& surfaces,
                            double stamp, const std::optional<WeakDirectionPrior>& prior,
                            const SensorPriors& sensor_priors, Eigen::Isometry3d& pose,
                            MappingOutput& out) {
  LocalizationTracker& tracker = *localization_;
  // A first sweep that could not be de-skewed is no fit for the map: the next one is aligned.
  const bool deskewed = !(scans_ == 0 && first_sweep_distorted_);
  bool aligned_now = false;
  if (deskewed && tracker.alignment_due(stamp)) {
    const LoopDetection alignment =
        tracker.align(keyframes_, make_keyframe(features, stamp, pose, false), stamp);
    aligned_now = alignment.accepted();
    if (alignment.accepted()) {
      pose = alignment.correction * pose;
      local_map_.update(keyframes_, pose.translation());
    }
  }
  if (tracker.state() == LocalizationState::kTracking) {
    out.match = matcher_.match(corners, surfaces, local_map_, pose, prior, wall_normals_,
                               aligned_now ? SensorPriors() : sensor_priors);
    pose = out.match.pose;
    tracker.assess(out.match, corners.size() + surfaces.size());
    // The last scans before the track was lost may have put wrong keyframes in the map.
    if (tracker.state() == LocalizationState::kLost) retire_recent_keyframes(0);
  }
  out.localization = tracker.take_status();
  return tracker.state() == LocalizationState::kTracking;
}

std::vector<Eigen::Isometry3d> LidarMapping::trajectory() const {
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(anchors_.size());
  for (const auto& [keyframe, relative] : anchors_) {
    poses.push_back(keyframe < 0 ? relative : keyframes_[keyframe].pose * relative);
  }
  return poses;
}

}  // namespace adaptive_lego_loam
