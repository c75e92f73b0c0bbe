#include "adaptive_lego_loam/sim/trajectory.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/sim/random.h"

namespace adaptive_lego_loam::sim {
namespace {

constexpr int kWavesPerAxis = 4;

double degrees_to_radians(double degrees) {
  return degrees * M_PI / 180.0;
}

}  // namespace

Shake::Shake(const ShakeParams& params, uint64_t seed) {
  Rng rng(seed);
  // kWavesPerAxis waves in [min_hz, max_hz] appended to `waves`, their amplitudes summing to
  // `bound`.
  auto add_waves = [&rng](double bound, double min_hz, double max_hz, std::vector<Wave>& waves) {
    std::vector<Wave> added(kWavesPerAxis);
    double weight_sum = 0.0;
    for (Wave& wave : added) {
      wave.amplitude = rng.uniform(0.5, 1.0);
      wave.frequency_hz = rng.uniform(min_hz, max_hz);
      wave.phase = rng.uniform(0.0, 2.0 * M_PI);
      weight_sum += wave.amplitude;
    }
    for (Wave& wave : added)
      wave.amplitude *= bound / weight_sum;
    waves.insert(waves.end(), added.begin(), added.end());
  };
  const double body_low = params.body_min_hz, body_high = params.body_max_hz;
  add_waves(params.vertical_m, body_low, body_high, vertical_);
  add_waves(degrees_to_radians(params.roll_deg), body_low, body_high, roll_);
  add_waves(degrees_to_radians(params.pitch_deg), body_low, body_high, pitch_);
  const double vibration_low = params.vibration_min_hz, vibration_high = params.vibration_max_hz;
  const double vibration_angle = degrees_to_radians(params.vibration_roll_pitch_deg);
  add_waves(params.vibration_vertical_m, vibration_low, vibration_high, vertical_);
  add_waves(vibration_angle, vibration_low, vibration_high, roll_);
  add_waves(vibration_angle, vibration_low, vibration_high, pitch_);
}

double Shake::sum(const std::vector<Wave>& waves, double time, int derivative) {
  double value = 0.0;
  for (const Wave& wave : waves) {
    const double omega = 2.0 * M_PI * wave.frequency_hz;
    const double angle = omega * time + wave.phase;
    if (derivative == 0) value += wave.amplitude * std::sin(angle);
    if (derivative == 1) value += wave.amplitude * omega * std::cos(angle);
    if (derivative == 2) value -= wave.amplitude * omega * omega * std::sin(angle);
  }
  return value;
}

Eigen::Matrix3d Shake::axes(double time) const {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Zero();
  if (vertical_.empty()) return axes;
  for (int derivative = 0; derivative < 3; ++derivative) {
    axes(0, derivative) = sum(vertical_, time, derivative);
    axes(1, derivative) = sum(roll_, time, derivative);
    axes(2, derivative) = sum(pitch_, time, derivative);
  }
  return axes;
}

Eigen::Isometry3d Shake::at(double time) const {
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  if (vertical_.empty()) return offset;
  offset.translation().z() = sum(vertical_, time);
  offset.linear() = (Eigen::AngleAxisd(sum(roll_, time), Eigen::Vector3d::UnitX()) *
                     Eigen::AngleAxisd(sum(pitch_, time), Eigen::Vector3d::UnitY()))
                        .toRotationMatrix();
  return offset;
}

PathTrajectory::PathTrajectory(std::shared_ptr<const Path> path, const SpeedProfile& speed,
                               double start_s, double lateral_offset, double sensor_height,
                               const Shake& shake, double frame_period)
    : path_(std::move(path)),
      speed_(speed),
      start_s_(start_s),
      lateral_offset_(lateral_offset),
      sensor_height_(sensor_height),
      shake_(shake),
      frame_period_(frame_period) {}

int PathTrajectory::frame_limit() const {
  if (path_->closed()) return INT_MAX;
  const double end_s = path_->length() - start_s_;  // keep as much road ahead as behind
  int frames = 0;
  while (arc_length(frame_time(frames) + frame_period_) <= end_s)
    ++frames;
  return frames;
}

const Shake& Trajectory::shake() const {
  static const Shake none;
  return none;
}

Eigen::Isometry3d PathTrajectory::sensor_pose(double time) const {
  return unshaken_pose(time) * shake_.at(time);
}

Eigen::Isometry3d PathTrajectory::unshaken_pose(double time) const {
  const Path::Frame frame = path_->at(arc_length(time));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(frame.position + lateral_offset_ * frame.left);
  pose.rotate(Eigen::AngleAxisd(frame.heading, Eigen::Vector3d::UnitZ()));
  pose.rotate(Eigen::AngleAxisd(-std::atan(frame.grade), Eigen::Vector3d::UnitY()));
  pose.translate(Eigen::Vector3d(0.0, 0.0, sensor_height_));
  return pose;
}

SampledTrajectory::SampledTrajectory(std::vector<double> times,
                                     std::vector<Eigen::Isometry3d> sensor_poses,
                                     const Shake& shake)
    : times_(std::move(times)), poses_(std::move(sensor_poses)), shake_(shake) {
  if (times_.size() != poses_.size() || times_.empty()) {
    throw std::invalid_argument("trajectory: " + std::to_string(times_.size()) + " times for " +
                                std::to_string(poses_.size()) + " poses");
  }
}

Eigen::Isometry3d SampledTrajectory::sensor_pose(double time) const {
  return unshaken_pose(time) * shake_.at(time);
}

Eigen::Isometry3d SampledTrajectory::unshaken_pose(double time) const {
  // Before the first sample the drive goes on as over its first step (the first sweep of a drive
  // entered at speed is skewed like the others); after the last it stands.
  const bool before = time < 0.0 && times_.size() > 1;
  const double t = before ? time + times_.front()
                          : std::clamp(time + times_.front(), times_.front(), times_.back());
  const auto after =
      before ? times_.begin() + 1 : std::upper_bound(times_.begin(), times_.end(), t);
  const std::size_t i =
      after == times_.end() ? times_.size() - 1 : static_cast<std::size_t>(after - times_.begin());
  if (i == 0 || times_[i] == t) return poses_[i];
  const double f = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
  const Eigen::Quaterniond q0(poses_[i - 1].linear()), q1(poses_[i].linear());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = (1.0 - f) * poses_[i - 1].translation() + f * poses_[i].translation();
  Eigen::Quaterniond rotation = q0.slerp(f, q1);
  if (before) rotation.normalize();  // slerp extrapolated near the identity is not unit
  pose.linear() = rotation.toRotationMatrix();
  return pose;
}

std::vector<Eigen::Isometry3d> camera_poses_to_vehicle_axes(
    const std::vector<Eigen::Isometry3d>& camera_poses) {
  Eigen::Isometry3d camera_to_vehicle = Eigen::Isometry3d::Identity();
  camera_to_vehicle.linear() << 0, 0, 1,  // vehicle x = camera z (forward)
      -1, 0, 0,                           // vehicle y = -camera x (left)
      0, -1, 0;                           // vehicle z = -camera y (up)
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(camera_poses.size());
  for (Eigen::Isometry3d pose : camera_poses) {
    pose.linear() = Eigen::Quaterniond(pose.linear()).normalized().toRotationMatrix();
    poses.push_back(camera_to_vehicle * pose * camera_to_vehicle.inverse());
  }
  return poses;
}

}  // namespace adaptive_lego_loam::sim
