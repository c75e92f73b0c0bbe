#include "adaptive_lego_loam/eval/metrics.h"

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/core/motion_sensors/wheel_odometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam {
namespace {

using Poses = std::vector<Eigen::Isometry3d>;

constexpr double kDegPerRad = 180.0 / EIGEN_PI;

void check_same_length(const Poses& estimate, const Poses& ground_truth) {
  if (estimate.empty() || ground_truth.empty()) {
    throw std::invalid_argument("empty trajectory (estimate " + std::to_string(estimate.size()) +
                                " poses, ground truth " + std::to_string(ground_truth.size()) +
                                ")");
  }
  if (estimate.size() != ground_truth.size()) {
    throw std::invalid_argument("trajectories differ in length (estimate " +
                                std::to_string(estimate.size()) + " poses, ground truth " +
                                std::to_string(ground_truth.size()) + ")");
  }
}

// (Q_a^-1 Q_b)^-1 (P_a^-1 P_b): the estimated motion from a to b seen from the true one.
Eigen::Isometry3d motion_error(const Poses& estimate, const Poses& ground_truth, std::size_t a,
                               std::size_t b) {
  const Eigen::Isometry3d true_motion = ground_truth[a].inverse() * ground_truth[b];
  const Eigen::Isometry3d estimated_motion = estimate[a].inverse() * estimate[b];
  return true_motion.inverse() * estimated_motion;
}

// Through the quaternion (atan2): accurate for small angles, unlike acos((trace - 1) / 2).
double rotation_angle_rad(const Eigen::Isometry3d& pose) {
  return Eigen::AngleAxisd(pose.linear()).angle();
}

double root_mean_square(const std::vector<double>& values) {
  double sum = 0;
  for (double value : values)
    sum += value * value;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

// distances[i]: ground-truth path length from frame 0 to frame i.
std::vector<double> path_distances(const Poses& poses) {
  std::vector<double> distances(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    distances[i] = distances[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  return distances;
}

void check_options(const KittiSegmentOptions& options) {
  if (options.start_every_frames < 1) {
    throw std::invalid_argument("start_every_frames must be at least 1");
  }
  for (double length : options.lengths_m) {
    if (!(length > 0)) throw std::invalid_argument("segment lengths must be positive");
  }
}

}  // namespace

RelativePoseError relative_pose_error(const Poses& estimate, const Poses& ground_truth) {
  check_same_length(estimate, ground_truth);
  RelativePoseError result;
  for (std::size_t i = 0; i + 1 < estimate.size(); ++i) {
    const Eigen::Isometry3d error = motion_error(estimate, ground_truth, i, i + 1);
    result.translation_m.push_back(error.translation().norm());
    result.rotation_deg.push_back(rotation_angle_rad(error) * kDegPerRad);
  }
  if (!result.translation_m.empty()) {
    result.translation_rmse_m = root_mean_square(result.translation_m);
    result.rotation_rmse_deg = root_mean_square(result.rotation_deg);
  }
  return result;
}

KittiSegmentError kitti_segment_error(const Poses& estimate, const Poses& ground_truth,
                                      const KittiSegmentOptions& options) {
  check_same_length(estimate, ground_truth);
  check_options(options);
  const std::vector<double> distances = path_distances(ground_truth);
  KittiSegmentError result;
  result.ground_truth_path_m = distances.back();
  double translation_sum = 0, rotation_sum = 0;
  for (double length : options.lengths_m) {
    SegmentLengthError per_length{length};
    for (std::size_t start = 0; start < distances.size(); start += options.start_every_frames) {
      const auto end_it =
          std::lower_bound(distances.begin() + start, distances.end(), distances[start] + length);
      if (end_it == distances.end()) break;  // later starts are nearer the end: none fits either
      const std::size_t end = static_cast<std::size_t>(end_it - distances.begin());
      const double path = distances[end] - distances[start];
      const Eigen::Isometry3d error = motion_error(estimate, ground_truth, start, end);
      const double translation_percent = 100.0 * error.translation().norm() / path;
      const double rotation_deg_per_100m = 100.0 * rotation_angle_rad(error) * kDegPerRad / path;
      ++per_length.segments;
      per_length.translation_percent += translation_percent;
      per_length.rotation_deg_per_100m += rotation_deg_per_100m;
      translation_sum += translation_percent;
      rotation_sum += rotation_deg_per_100m;
    }
    if (per_length.segments == 0) continue;
    result.segments += per_length.segments;
    per_length.translation_percent /= per_length.segments;
    per_length.rotation_deg_per_100m /= per_length.segments;
    result.per_length.push_back(per_length);
  }
  if (result.segments > 0) {
    result.translation_percent = translation_sum / result.segments;
    result.rotation_deg_per_100m = rotation_sum / result.segments;
  }
  return result;
}

AbsoluteTrajectoryError absolute_trajectory_error(const Poses& estimate,
                                                  const Poses& ground_truth) {
  check_same_length(estimate, ground_truth);
  const Eigen::Index n = static_cast<Eigen::Index>(estimate.size());
  Eigen::Matrix3Xd estimated_positions(3, n), true_positions(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    estimated_positions.col(i) = estimate[i].translation();
    true_positions.col(i) = ground_truth[i].translation();
  }
  AbsoluteTrajectoryError result;
  result.alignment.matrix() = Eigen::umeyama(estimated_positions, true_positions, false);
  const Eigen::Matrix3Xd residuals = ((result.alignment.linear() * estimated_positions).colwise() +
                                      result.alignment.translation()) -
                                     true_positions;
  result.rmse_m = std::sqrt(residuals.colwise().squaredNorm().mean());
  return result;
}

std::vector<Eigen::Isometry3d> camera_to_lidar_poses(const Poses& camera_poses,
                                                     const Eigen::Isometry3d& velo_to_cam) {
  // The general inverse, not the isometry one (transpose): KITTI's Tr is orthonormal only to
  // ~1e-7, and this way an identity camera pose still maps to the identity.
  const Eigen::Isometry3d cam_to_velo(velo_to_cam.inverse(Eigen::Affine).matrix());
  Poses lidar_poses;
  lidar_poses.reserve(camera_poses.size());
  for (const Eigen::Isometry3d& camera_pose : camera_poses)
    lidar_poses.push_back(cam_to_velo * camera_pose * velo_to_cam);
  return lidar_poses;
}

OdometryEvaluation evaluate_odometry(const Poses& estimate, const Poses& ground_truth,
                                     const KittiSegmentOptions& options) {
  OdometryEvaluation evaluation;
  evaluation.estimate_frames = estimate.size();
  evaluation.ground_truth_frames = ground_truth.size();
  evaluation.frames_used = std::min(estimate.size(), ground_truth.size());
  if (evaluation.frames_used == 0) check_same_length(estimate, ground_truth);  // throws
  const auto used = static_cast<std::ptrdiff_t>(evaluation.frames_used);
  const Poses estimate_used(estimate.begin(), estimate.begin() + used);
  const Poses truth_used(ground_truth.begin(), ground_truth.begin() + used);
  evaluation.rpe = relative_pose_error(estimate_used, truth_used);
  evaluation.kitti = kitti_segment_error(estimate_used, truth_used, options);
  evaluation.ate = absolute_trajectory_error(estimate_used, truth_used);
  evaluation.drift = end_drift(estimate_used, truth_used);
  return evaluation;
}

EndDrift end_drift(const Poses& estimate, const Poses& ground_truth) {
  check_same_length(estimate, ground_truth);
  EndDrift drift;
  drift.estimated_path_m = path_distances(estimate).back();
  drift.ground_truth_path_m = path_distances(ground_truth).back();
  if (drift.ground_truth_path_m > 0) {
    drift.reach_ratio = drift.estimated_path_m / drift.ground_truth_path_m;
  }
  const Eigen::Vector2d end = estimate.back().translation().head<2>();
  // The nearest point of the true path, horizontally; its first and last steps that move run on
  // straight.
  auto step_of = [&](std::size_t i) -> Eigen::Vector2d {
    return (ground_truth[i + 1].translation() - ground_truth[i].translation()).head<2>();
  };
  std::vector<std::size_t> moving;
  for (std::size_t i = 0; i + 1 < ground_truth.size(); ++i) {
    if (step_of(i).norm() > 0) moving.push_back(i);
  }
  double arc = 0, best_distance = std::numeric_limits<double>::infinity(), best_arc = 0;
  for (std::size_t i : moving) {
    const Eigen::Vector2d a = ground_truth[i].translation().head<2>(), step = step_of(i);
    const double length = step.norm();
    double along = (end - a).dot(step) / length;
    if (i != moving.front()) along = std::max(along, 0.0);
    if (i != moving.back()) along = std::min(along, length);
    const double distance = (end - a - along * step / length).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best_arc = arc + along;
    }
    arc += length;
  }
  if (arc > 0) {
    drift.along_track_percent = 100.0 * (best_arc - arc) / arc;
    drift.cross_track_percent = 100.0 * best_distance / arc;
  }
  return drift;
}

Poses constant_velocity_baseline(const Poses& ground_truth, std::size_t window_frames) {
  if (ground_truth.empty()) throw std::invalid_argument("empty ground truth");
  const std::size_t k = std::min(window_frames, ground_truth.size() - 1);
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  if (k > 0) {
    // The step S with S^k = Q_0^-1 Q_k: a k-th of the rotation, and the translation that k such
    // steps add up to.
    const Eigen::Isometry3d motion = ground_truth.front().inverse() * ground_truth[k];
    const Eigen::AngleAxisd rotation(motion.linear());
    step.linear() = Eigen::AngleAxisd(rotation.angle() / static_cast<double>(k), rotation.axis())
                        .toRotationMatrix();
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero(), power = Eigen::Matrix3d::Identity();
    for (std::size_t j = 0; j < k; ++j, power = power * step.linear())
      sum += power;
    step.translation() = sum.inverse() * motion.translation();
  }
  Poses baseline{ground_truth.front()};
  while (baseline.size() < ground_truth.size())
    baseline.push_back(baseline.back() * step);
  return baseline;
}

Poses wheel_baseline(const Poses& ground_truth, const std::vector<double>& times,
                     const std::vector<WheelOdometrySample>& samples,
                     const WheelOdometryParams& params) {
  if (ground_truth.empty()) throw std::invalid_argument("empty ground truth");
  if (times.size() < ground_truth.size()) {
    throw std::invalid_argument("scan times (" + std::to_string(times.size()) +
                                ") fewer than the ground truth's poses (" +
                                std::to_string(ground_truth.size()) + ")");
  }
  std::deque<WheelOdometrySample> shifted(samples.begin(), samples.end());
  for (WheelOdometrySample& sample : shifted)
    sample.stamp += params.time_offset_s;
  const Eigen::Isometry3d lidar_from_base =
      pose_from_rpy_xyz(params.extrinsic_rpy_deg.data(), params.extrinsic_xyz_m.data());
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  Poses baseline{ground_truth.front()};
  for (std::size_t i = 1; i < ground_truth.size(); ++i) {
    if (const auto wheel = integrate_wheel(shifted, times[i - 1], times[i], params)) {
      step = lidar_from_base * wheel->motion * lidar_from_base.inverse();
    }
    baseline.push_back(baseline.back() * step);
  }
  return baseline;
}

std::size_t steps_within(const std::vector<double>& times, double seconds) {
  std::size_t k = 0;
  while (k + 1 < times.size() && times[k + 1] - times.front() <= seconds + 1e-9)
    ++k;
  return k;
}

}  // namespace adaptive_lego_loam
