#include "adaptive_lego_loam/core/pipeline/lidar_mapping.h"

#include <cmath>

#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

namespace adaptive_lego_loam {

namespace {
constexpr double kLoopAttemptPeriod = 1.0;  // s
}  // namespace

LidarMapping::LidarMapping(const Config& config)
    : params_(config.mapping),
      loop_params_(config.loop_closure),
      first_sweep_distorted_(!config.sensor.deskewed),
      graph_(config.loop_closure),
      local_map_(config.mapping),
      merger_(config.mapping),
      matcher_(config.mapping) {}

void LidarMapping::start_loop_closure(double stamp) {
  const int newest = static_cast<int>(keyframes_.size()) - 1;
  // The candidate search is cheap and runs at every keyframe; the rest at most once a period.
  if (find_loop_candidate(keyframes_, newest, loop_params_) < 0) return;
  if (stamp - last_loop_attempt_ < kLoopAttemptPeriod) return;
  last_loop_attempt_ = stamp;
  loop_job_.emplace(keyframes_, newest, loop_params_);
}

std::optional<LoopDetection> LidarMapping::advance_loop_closure(double stamp, bool new_keyframe) {
  if (!loop_params_.enabled) return std::nullopt;
  if (new_keyframe && !loop_closure_running()) start_loop_closure(stamp);
  if (loop_job_) {
    if (!loop_job_->step()) return std::nullopt;
    const LoopDetection detection = loop_job_->detection();
    loop_job_.reset();
    if (!detection.accepted()) return detection;
    // The pose graph's first step waits for the next scan.
    loop_optimization_.emplace(graph_, detection, loop_params_);
    return std::nullopt;
  }
  if (!loop_optimization_ || !loop_optimization_->step()) return std::nullopt;
  const LoopDetection loop = loop_optimization_->loop();
  close_loop();
  return loop;
}

void LidarMapping::close_loop() {
  const Eigen::Isometry3d motion = loop_optimization_->apply(graph_, keyframes_);
  loop_optimization_.reset();
  // The running pose moves with the newest keyframe; the local map is placed again from the
  // corrected keyframes.
  pose_ = motion * pose_;
  local_map_.keyframes_moved(motion);
  ++loops_closed_;
}

std::optional<LoopDetection> LidarMapping::finish_loop_closure() {
  std::optional<LoopDetection> finished;
  while (loop_closure_running() && !finished) {
    finished = advance_loop_closure(0.0, false);
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

bool LidarMapping::needs_keyframe() const {
  if (keyframes_.empty()) return true;
  const Eigen::Isometry3d since = keyframes_.back().pose.inverse() * pose_;
  return since.translation().norm() >= params_.keyframe_distance ||
         Eigen::AngleAxisd(since.linear()).angle() >= params_.keyframe_angle_deg * M_PI / 180.0;
}

void LidarMapping::add_keyframe(const FeatureSet& features, double stamp) {
  Keyframe keyframe;
  keyframe.index = static_cast<int>(keyframes_.size());
  keyframe.frame = scans_;
  keyframe.stamp = stamp;
  keyframe.pose = pose_;
  keyframe.corners = pack(*keyframe_filter_(*features.less_sharp, params_.corner_voxel));
  keyframe.surfaces =
      pack(*keyframe_filter_(*features.less_flat, *features.outliers, params_.surface_voxel));
  graph_.add_keyframe(keyframe);
  keyframes_.push_back(std::move(keyframe));
  merger_.merge_old(keyframes_);
}

void LidarMapping::process(const FeatureSet& features, const Eigen::Isometry3d& odometry_pose,
                           double stamp, const std::optional<WeakDirectionPrior>& prior,
                           MappingOutput& out) {
  Stopwatch watch;
  out.times.clear();
  const Eigen::Isometry3d motion = last_odometry_pose_
                                       ? last_odometry_pose_->inverse() * odometry_pose
                                       : Eigen::Isometry3d::Identity();
  last_odometry_pose_ = odometry_pose;
  // A large object moving along with the sensor (a truck overtaking) can drag the scan-to-scan
  // estimate; scan-to-map then starts from the previous velocity instead.
  out.motion_gated = !motion_is_plausible(motion);
  Eigen::Isometry3d pose = pose_ * (out.motion_gated ? *last_mapped_motion_ : motion);
  const Eigen::Isometry3d previous_pose = pose_;
  out.match = MapMatchResult();
  out.match.pose = pose;

  if (params_.enabled && !keyframes_.empty()) {
    local_map_.update(keyframes_, pose.translation());
    out.times.add("local_map", watch.lap_ms());
    const CloudPtr corners = scan_filter_(*features.less_sharp, params_.scan_corner_voxel);
    const CloudPtr surfaces =
        scan_filter_(*features.less_flat, *features.outliers, params_.scan_surface_voxel);
    out.match = matcher_.match(*corners, *surfaces, local_map_, pose, prior);
    pose = out.match.pose;
    out.times.add("mapping", watch.lap_ms());
  }
  pose_ = pose;
  // The velocity exists once two scans have been mapped.
  if (scans_ >= 1) last_mapped_motion_ = previous_pose.inverse() * pose_;
  fusion_.update_mapping(odometry_pose, pose_);
  out.pose = pose_;
  out.keyframe = !(scans_ == 0 && first_sweep_distorted_) && needs_keyframe();
  if (out.keyframe) {
    add_keyframe(features, stamp);
    out.times.add("keyframes", watch.lap_ms());
  }
  const bool loop_work = out.keyframe || loop_closure_running();
  out.loop = advance_loop_closure(stamp, out.keyframe);
  if (loop_work) out.times.add("loop_closure", watch.lap_ms());
  if (out.loop && out.loop->accepted()) {
    out.pose = pose_;
    fusion_.update_mapping(odometry_pose, pose_);
  }
  if (keyframes_.empty()) {
    anchors_.emplace_back(-1, pose_);  // no keyframe yet: the pose itself
  } else {
    const Keyframe& anchor = keyframes_.back();
    anchors_.emplace_back(anchor.index, anchor.pose.inverse() * pose_);
  }
  ++scans_;
  out.times.add("keyframes", watch.lap_ms());
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
