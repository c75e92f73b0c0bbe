#pragma once
// Localization on a saved map: whether the scans are tracked against it, and the alignment that
// finds the map at the start, after a restart and while lost. LidarMapping's localization mode
// runs it; the map's keyframes stay as they were saved.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/loop_closure/loop_detection.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"
#include "adaptive_lego_loam/core/mapping/scan_to_map.h"

namespace adaptive_lego_loam {

// kAligning: not aligned yet (the start, or a new initial pose); kLost: an alignment or the
// tracking failed, and the pose follows the odometry while alignments are retried.
enum class LocalizationState { kAligning, kTracking, kLost };
const char* to_string(LocalizationState state);

// A start pose as a user gives it: a position in the map and a heading (deg), level.
Eigen::Isometry3d initial_pose(double x, double y, double z, double yaw_deg);

struct LocalizationStatus {
  LocalizationState state = LocalizationState::kAligning;
  double match_ratio = 0.0;  // of this scan's features that found a line or plane in the map
  // The alignment that ran on this scan, if one did.
  std::optional<LoopDetection> alignment;
};

class LocalizationTracker {
 public:
  // The first `map_keyframes` keyframes are the saved map's.
  LocalizationTracker(const LocalizationParams& params, const LoopClosureParams& verification,
                      int map_keyframes);

  int map_keyframes() const { return map_keyframes_; }
  LocalizationState state() const { return state_; }
  // Starts over from a new pose: the next scan is aligned.
  void restart();
  // Aligning (every scan, at the start or after a new initial pose), or lost and the retry
  // period has passed since the last alignment.
  bool alignment_due(double stamp) const;
  // ICP of `scan` (a keyframe made of this scan's features, posed at the guess) to the map
  // keyframes around the one nearest the guess, accepted by loop closure's inlier test: tracking
  // when it is; when not, lost (while aligning: after lost_after_scans failed scans). kNoCandidate
  // when no map keyframe lies within search_radius.
  LoopDetection align(const std::vector<Keyframe>& keyframes, Keyframe scan, double stamp);
  // Scan-to-map's result of a tracked scan with `points` features: a ratio of matched ones below
  // min_match_ratio for lost_after_scans scans in a row loses the track.
  void assess(const MapMatchResult& match, std::size_t points);
  // This scan's status; `alignment` is moved out (reported once).
  LocalizationStatus take_status();

 private:
  std::optional<LoopCandidate> nearest_map_keyframe(const std::vector<Keyframe>& keyframes,
                                                    const Eigen::Isometry3d& guess) const;

  LocalizationParams params_;
  LoopClosureParams verification_;
  int map_keyframes_;
  LocalizationState state_ = LocalizationState::kAligning;
  int scans_below_ = 0;
  double last_alignment_ = -1e18;
  LocalizationStatus status_;
};

}  // namespace adaptive_lego_loam
