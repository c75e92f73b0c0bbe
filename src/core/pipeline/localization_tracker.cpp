#include "adaptive_lego_loam/core/pipeline/localization_tracker.h"

#include <cmath>
#include <limits>

namespace adaptive_lego_loam {

const char* to_string(LocalizationState state) {
  switch (state) {
    case LocalizationState::kAligning:
      return "aligning";
    case LocalizationState::kTracking:
      return "tracking";
    case LocalizationState::kLost:
      return "lost";
  }
  return "unknown";
}

Eigen::Isometry3d initial_pose(double x, double y, double z, double yaw_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  pose.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  return pose;
}

LocalizationTracker::LocalizationTracker(const LocalizationParams& params,
                                         const LoopClosureParams& verification, int map_keyframes)
    : params_(params), verification_(verification), map_keyframes_(map_keyframes) {
  // The map's stamps come from another drive: every map keyframe may take part.
  verification_.enabled = true;
  verification_.min_time_gap = -std::numeric_limits<double>::infinity();
}

void LocalizationTracker::restart() {
  state_ = LocalizationState::kAligning;
  scans_below_ = 0;
  last_alignment_ = -1e18;
}

bool LocalizationTracker::alignment_due(double stamp) const {
  if (state_ == LocalizationState::kAligning) return true;
  return state_ == LocalizationState::kLost && stamp - last_alignment_ >= params_.retry_period;
}

std::optional<LoopCandidate> LocalizationTracker::nearest_map_keyframe(
    const std::vector<Keyframe>& keyframes, const Eigen::Isometry3d& guess) const {
  int nearest = -1;
  double nearest_distance = params_.search_radius;
  for (int i = 0; i < map_keyframes_; ++i) {
    if (!keyframes[i].has_clouds()) continue;
    const double distance = (keyframes[i].pose.translation() - guess.translation()).norm();
    if (distance <= nearest_distance) {
      nearest = i;
      nearest_distance = distance;
    }
  }
  if (nearest < 0) return std::nullopt;
  LoopCandidate candidate;
  candidate.matched_index = nearest;
  candidate.guess = guess;
  return candidate;
}

LoopDetection LocalizationTracker::align(const std::vector<Keyframe>& keyframes, Keyframe scan,
                                         double stamp) {
  last_alignment_ = stamp;
  // The map's keyframes and the scan after them: the scan is the loop's "current" keyframe.
  std::vector<Keyframe> scene(keyframes.begin(), keyframes.begin() + map_keyframes_);
  scan.index = map_keyframes_;
  const std::optional<LoopCandidate> candidate = nearest_map_keyframe(keyframes, scan.pose);
  scene.push_back(std::move(scan));
  LoopDetection alignment = detect_loop(scene, map_keyframes_, candidate, verification_);
  if (alignment.accepted()) {
    state_ = LocalizationState::kTracking;
    scans_below_ = 0;
  } else if (state_ != LocalizationState::kAligning || ++scans_below_ >= params_.lost_after_scans) {
    // A start (or restart) gets lost_after_scans scans to align: the first ones after a start
    // at speed are the least well de-skewed.
    state_ = LocalizationState::kLost;
    scans_below_ = 0;
  }
  status_.alignment = alignment;
  return alignment;
}

void LocalizationTracker::assess(const MapMatchResult& match, std::size_t points) {
  status_.match_ratio =
      points == 0 ? 0.0 : double(match.edge_matches + match.plane_matches) / double(points);
  if (status_.match_ratio >= params_.min_match_ratio) {
    scans_below_ = 0;
    return;
  }
  if (++scans_below_ >= params_.lost_after_scans) {
    state_ = LocalizationState::kLost;
    last_alignment_ = -1e18;  // the next scan tries at once
  }
}

LocalizationStatus LocalizationTracker::take_status() {
  status_.state = state_;
  LocalizationStatus status = std::move(status_);
  status_ = LocalizationStatus();
  return status;
}

}  // namespace adaptive_lego_loam
