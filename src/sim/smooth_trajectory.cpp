#include "adaptive_lego_loam/sim/smooth_trajectory.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam::sim {
namespace {

struct Knots {
  std::vector<double> times;
  Eigen::MatrixXd positions;
  std::vector<Eigen::Matrix3d> rotations;
};

Knots knots_of(const Trajectory& base, int frames) {
  const int count = std::min(frames + 2, base.frame_limit());
  if (count < 1) throw std::invalid_argument("smooth trajectory: no frame times");
  Knots knots;
  knots.positions.resize(std::max(count, 2), 3);
  for (int frame = 0; frame < count; ++frame) {
    const double time = base.frame_time(frame);
    const Eigen::Isometry3d pose = base.unshaken_pose(time);
    knots.times.push_back(time);
    knots.positions.row(frame) = pose.translation().transpose();
    knots.rotations.push_back(pose.linear());
  }
  if (count == 1) {  // a single pose: standing there
    knots.times.push_back(knots.times.front() + 1.0);
    knots.positions.row(1) = knots.positions.row(0);
    knots.rotations.push_back(knots.rotations.front());
  }
  return knots;
}

// A rotation about one axis by an angle with its two time derivatives.
Kinematics turn(const Eigen::Vector3d& axis, const Eigen::Vector3d& angle) {
  Kinematics k;
  k.pose.linear() = Eigen::AngleAxisd(angle(0), axis).toRotationMatrix();
  k.angular_velocity = angle(1) * axis;
  k.angular_acceleration = angle(2) * axis;
  return k;
}

SmoothingSpline position_spline(const Trajectory& base, int frames, double cutoff_hz) {
  const Knots knots = knots_of(base, frames);
  return SmoothingSpline(knots.times, knots.positions, cutoff_hz);
}

RotationSpline rotation_spline(const Trajectory& base, int frames) {
  Knots knots = knots_of(base, frames);
  return RotationSpline(knots.times, std::move(knots.rotations));
}

}  // namespace

SmoothTrajectory::SmoothTrajectory(std::shared_ptr<const Trajectory> base, int frames,
                                   double position_cutoff_hz)
    : base_(std::move(base)),
      position_cutoff_hz_(position_cutoff_hz),
      positions_(position_spline(*base_, frames, position_cutoff_hz)),
      rotations_(rotation_spline(*base_, frames)) {
  frame_limit_ = std::min(frames + 2, base_->frame_limit());
}

Eigen::Isometry3d SmoothTrajectory::sensor_pose(double time) const {
  return unshaken_pose(time) * shake().at(time);
}

Eigen::Isometry3d SmoothTrajectory::unshaken_pose(double time) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotations_.at(time).rotation;
  pose.translation() = positions_.at(time);
  return pose;
}

Kinematics SmoothTrajectory::unshaken_motion(double time) const {
  const RotationSpline::State rotation = rotations_.at(time);
  Kinematics k;
  k.pose.linear() = rotation.rotation;
  k.pose.translation() = positions_.at(time);
  k.velocity = positions_.at(time, 1);
  k.acceleration = positions_.at(time, 2);
  k.angular_velocity = rotation.angular_velocity;
  k.angular_acceleration = rotation.angular_acceleration;
  return k;
}

// Shake::at's offset: up by the vertical offset, then Rx(roll) Ry(pitch).
Kinematics SmoothTrajectory::shake_motion(double time) const {
  const Eigen::Matrix3d axes = shake().axes(time);
  Kinematics vertical;
  vertical.pose.translation().z() = axes(0, 0);
  vertical.velocity.z() = axes(0, 1);
  vertical.acceleration.z() = axes(0, 2);
  const Kinematics roll = turn(Eigen::Vector3d::UnitX(), axes.row(1).transpose());
  const Kinematics pitch = turn(Eigen::Vector3d::UnitY(), axes.row(2).transpose());
  return compose(vertical, compose(roll, pitch));
}

Kinematics SmoothTrajectory::motion(double time) const {
  Kinematics k = compose(unshaken_motion(time), shake_motion(time));
  k.pose = sensor_pose(time);  // bit for bit the pose the scans are rendered from
  return k;
}

std::vector<double> sample_times(double from, double to, double rate_hz) {
  std::vector<double> times;
  for (long k = 0;; ++k) {
    const double time = from + static_cast<double>(k) / rate_hz;
    if (time > to + 1e-9) break;
    times.push_back(time);
  }
  return times;
}

}  // namespace adaptive_lego_loam::sim
