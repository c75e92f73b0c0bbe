#pragma once
// Odometry metrics of docs/METHOD.md (Metrics): RPE per frame, the KITTI segment metric, ATE
// after a rigid alignment, and the drift at the end of a drive (how far it got along the road). P
// is the estimate, Q the ground truth; both are poses of the same sensor frame in that trajectory's
// first frame (x_world = pose * x_sensor). Index i of one trajectory is the same scan as index i of
// the other.
//
// The metric functions throw std::invalid_argument when the trajectories are empty or differ in
// length; evaluate_odometry() takes their common prefix instead.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam {

// E_i = (Q_i^-1 Q_{i+1})^-1 (P_i^-1 P_{i+1}) for each consecutive pair.
struct RelativePoseError {
  std::vector<double> translation_m;         // |t(E_i)|, one entry per pair (i, i+1)
  std::vector<double> rotation_deg;          // angle of R(E_i)
  std::optional<double> translation_rmse_m;  // empty with fewer than two poses
  std::optional<double> rotation_rmse_deg;
};

RelativePoseError relative_pose_error(const std::vector<Eigen::Isometry3d>& estimate,
                                      const std::vector<Eigen::Isometry3d>& ground_truth);

struct KittiSegmentOptions {
  std::vector<double> lengths_m{100, 200, 300, 400, 500, 600, 700, 800};
  int start_every_frames = 10;
};

struct SegmentLengthError {
  double length_m = 0;
  int segments = 0;
  double translation_percent = 0;
  double rotation_deg_per_100m = 0;
};

// A segment starts at every start_every_frames-th frame and ends at the first frame whose
// ground-truth path length from the start is at least the segment length. Its error is
// E = (Q_s^-1 Q_e)^-1 (P_s^-1 P_e); translation |t(E)| in % and rotation angle(E) in deg per
// 100 m, both divided by the segment's ground-truth path length. Averages are over segments.
// Units: KITTI's devkit reports the rotation in deg/m; ours is 100 times that.
struct KittiSegmentError {
  double ground_truth_path_m = 0;  // the whole ground-truth path
  int segments = 0;
  // Empty when no segment fits: the path is shorter than the shortest segment length.
  std::optional<double> translation_percent;
  std::optional<double> rotation_deg_per_100m;
  std::vector<SegmentLengthError> per_length;  // only lengths with at least one segment
};

KittiSegmentError kitti_segment_error(const std::vector<Eigen::Isometry3d>& estimate,
                                      const std::vector<Eigen::Isometry3d>& ground_truth,
                                      const KittiSegmentOptions& options = {});

struct AbsoluteTrajectoryError {
  // The rigid motion (Umeyama, no scale) that best maps the estimated positions onto the ground
  // truth's: alignment * t(P_i) ~ t(Q_i).
  Eigen::Isometry3d alignment = Eigen::Isometry3d::Identity();
  double rmse_m = 0;  // of |alignment * t(P_i) - t(Q_i)|
};

AbsoluteTrajectoryError absolute_trajectory_error(
    const std::vector<Eigen::Isometry3d>& estimate,
    const std::vector<Eigen::Isometry3d>& ground_truth);

// KITTI's ground truth is the left camera's pose; with Tr the velodyne-to-camera transform
// (calib.txt), the lidar's pose is Tr^-1 * P_cam * Tr.
std::vector<Eigen::Isometry3d> camera_to_lidar_poses(
    const std::vector<Eigen::Isometry3d>& camera_poses, const Eigen::Isometry3d& velo_to_cam);

// Where the estimated drive ended up relative to the true path, in the horizontal (x-y) plane of
// the trajectories' frame. A degenerate scene (a tunnel) shows as an estimate that falls short or
// runs on along the road (along-track) rather than one that leaves it (cross-track).
struct EndDrift {
  double estimated_path_m = 0;  // sum of the estimate's steps
  double ground_truth_path_m = 0;
  // Estimated over true path length; empty when the true path has no length.
  std::optional<double> reach_ratio;
  // The estimated end projected onto the true path (its first and last steps extended straight
  // on): its arc length minus the true end's, % of the true path's horizontal length. Negative:
  // the estimate fell short.
  std::optional<double> along_track_percent;
  // The estimated end's horizontal distance from the true path, % of its horizontal length.
  std::optional<double> cross_track_percent;
};

// Over the whole of both trajectories (same length, not empty; std::invalid_argument otherwise).
EndDrift end_drift(const std::vector<Eigen::Isometry3d>& estimate,
                   const std::vector<Eigen::Isometry3d>& ground_truth);

// Dead reckoning at the ground truth's mean velocity over its first `window_frames` steps (in the
// sensor frame: the motion Q_0^-1 Q_k spread evenly over k steps), kept for the whole drive from
// the first true pose: what a constant-velocity guess gets without any scan. With fewer poses
// than the window, over those there are.
std::vector<Eigen::Isometry3d> constant_velocity_baseline(
    const std::vector<Eigen::Isometry3d>& ground_truth, std::size_t window_frames);

// Dead reckoning on the wheel odometry alone from the first true pose: between consecutive scan
// `times` the base frame's motion as the odometry reports it (scale and slips uncorrected,
// core's integrate_wheel), moved to the sensor frame by the config's extrinsic; across a gap in
// the samples the last motion is kept. What the wheels alone get. Needs a time per pose.
std::vector<Eigen::Isometry3d> wheel_baseline(const std::vector<Eigen::Isometry3d>& ground_truth,
                                              const std::vector<double>& times,
                                              const std::vector<WheelOdometrySample>& samples,
                                              const WheelOdometryParams& params);

// How many steps the first `seconds` of scan times (increasing) span: the largest k with
// times[k] - times[0] <= seconds.
std::size_t steps_within(const std::vector<double>& times, double seconds);

struct OdometryEvaluation {
  std::size_t estimate_frames = 0;
  std::size_t ground_truth_frames = 0;
  std::size_t frames_used = 0;  // the common prefix, e.g. of an interrupted run
  RelativePoseError rpe;
  KittiSegmentError kitti;
  AbsoluteTrajectoryError ate;
  EndDrift drift;
};

// All the metrics over the common prefix of the two trajectories. Throws std::invalid_argument
// when either is empty.
OdometryEvaluation evaluate_odometry(const std::vector<Eigen::Isometry3d>& estimate,
                                     const std::vector<Eigen::Isometry3d>& ground_truth,
                                     const KittiSegmentOptions& options = {});

}  // namespace adaptive_lego_loam
