#pragma once
// Smooth trajectories for the motion sensors' tests: analytic drives sampled at 10 Hz and joined
// by SmoothTrajectory, as the scene generator joins its drives.

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/sim/smooth_trajectory.h"
#include "adaptive_lego_loam/sim/trajectory.h"

namespace adaptive_lego_loam::sim::test {

using PoseFunction = std::function<Eigen::Isometry3d(double)>;

// `pose` at 0, 0.1, ... `seconds` s, with `shake` on top, joined smoothly.
inline std::shared_ptr<const SmoothTrajectory> smooth_drive(const PoseFunction& pose,
                                                            double seconds,
                                                            const Shake& shake = Shake()) {
  std::vector<double> times;
  std::vector<Eigen::Isometry3d> poses;
  const int frames = static_cast<int>(std::lround(seconds / 0.1));
  for (int i = 0; i <= frames + 1; ++i) {
    times.push_back(0.1 * i);
    poses.push_back(pose(0.1 * i));
  }
  auto base = std::make_shared<SampledTrajectory>(times, poses, shake);
  return std::make_shared<SmoothTrajectory>(base, frames, 0.0);
}

// Level, at `speed` m/s round a circle at `yaw_rate` rad/s (left when positive), from the
// origin along x.
inline PoseFunction turning(double speed, double yaw_rate) {
  return [=](double t) {
    const double heading = yaw_rate * t, radius = speed / yaw_rate;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() =
        Eigen::Vector3d(radius * std::sin(heading), radius * (1.0 - std::cos(heading)), 0.0);
    return pose;
  };
}

// A winding, hilly drive at a varying speed that rolls and pitches a little.
inline PoseFunction winding() {
  return [](double time) {
    const Eigen::Vector3d position(9.0 * time + 4.0 * std::sin(0.3 * time),
                                   15.0 * std::sin(0.15 * time), 0.8 * std::sin(0.4 * time));
    const Eigen::Vector3d velocity(9.0 + 1.2 * std::cos(0.3 * time), 2.25 * std::cos(0.15 * time),
                                   0.32 * std::cos(0.4 * time));
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = position;
    pose.linear() =
        (Eigen::AngleAxisd(std::atan2(velocity.y(), velocity.x()), Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(-0.03 * std::sin(0.4 * time), Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(0.02 * std::sin(0.7 * time), Eigen::Vector3d::UnitX()))
            .toRotationMatrix();
    return pose;
  };
}

inline std::shared_ptr<const SmoothTrajectory> standing(double seconds) {
  return smooth_drive([](double) { return Eigen::Isometry3d::Identity(); }, seconds);
}

}  // namespace adaptive_lego_loam::sim::test
