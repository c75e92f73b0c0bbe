#pragma once
// Exact IMU and wheel-odometry samples of a smooth trajectory for tests: derivatives by central
// differences of the trajectory's poses (exact to about 1e-7 for the motions tests use).

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam::test {

// A body's pose in a level world (z up) at time t.
using PoseAt = std::function<Eigen::Isometry3d(double)>;

// Driving a circle of radius speed / yaw_rate at constant speed, level, from the origin along x.
inline PoseAt constant_turn(double speed, double yaw_rate) {
  return [=](double t) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const double heading = yaw_rate * t;
    pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    if (yaw_rate == 0.0) {
      pose.translation() = Eigen::Vector3d(speed * t, 0.0, 0.0);
    } else {
      const double radius = speed / yaw_rate;
      pose.translation() =
          Eigen::Vector3d(radius * std::sin(heading), radius * (1.0 - std::cos(heading)), 0.0);
    }
    return pose;
  };
}

// What an IMU rigidly mounted at `body_from_imu` on the body reads at time t, gravity g.
inline ImuSample imu_sample(const PoseAt& body, double t, const Eigen::Isometry3d& body_from_imu,
                            double gravity = 9.81) {
  constexpr double h = 1e-3;
  const auto imu = [&](double time) { return body(time) * body_from_imu; };
  const Eigen::Isometry3d before = imu(t - h), now = imu(t), after = imu(t + h);
  ImuSample sample;
  sample.stamp = t;
  sample.angular_velocity = rotation_log(before.linear().transpose() * after.linear()) / (2.0 * h);
  const Eigen::Vector3d acceleration =
      (after.translation() - 2.0 * now.translation() + before.translation()) / (h * h);
  sample.linear_acceleration =
      now.linear().transpose() * (acceleration + Eigen::Vector3d(0.0, 0.0, gravity));
  return sample;
}

// IMU samples at `rate` Hz over [from, to].
inline std::vector<ImuSample> imu_samples(const PoseAt& body, double from, double to, double rate,
                                          const Eigen::Isometry3d& body_from_imu) {
  std::vector<ImuSample> samples;
  for (int i = 0; from + i / rate <= to + 1e-9; ++i)
    samples.push_back(imu_sample(body, from + i / rate, body_from_imu));
  return samples;
}

// What a wheel odometry of the base at `body_from_base` reports at time t (exact, scaled).
inline WheelOdometrySample wheel_sample(const PoseAt& body, double t,
                                        const Eigen::Isometry3d& body_from_base,
                                        double scale = 1.0) {
  constexpr double h = 1e-3;
  const auto base = [&](double time) { return body(time) * body_from_base; };
  const Eigen::Isometry3d before = base(t - h), now = base(t), after = base(t + h);
  WheelOdometrySample sample;
  sample.stamp = t;
  sample.angular_velocity = rotation_log(before.linear().transpose() * after.linear()) / (2.0 * h);
  sample.linear_velocity =
      scale * now.linear().transpose() * (after.translation() - before.translation()) / (2.0 * h);
  return sample;
}

}  // namespace adaptive_lego_loam::test
