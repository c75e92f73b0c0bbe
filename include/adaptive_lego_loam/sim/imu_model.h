#pragma once
// A MEMS IMU mounted on the LiDAR, read along the smooth trajectory: the angular velocity and
// specific force of its own frame (the lever arm included), with the errors its datasheet gives:
// white noise, a bias random walk and a turn-on bias drawn per seed.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"
#include "adaptive_lego_loam/sim/kinematics.h"
#include "adaptive_lego_loam/sim/smooth_trajectory.h"

namespace adaptive_lego_loam::sim {

// An IMU's error figures as its datasheet gives them, in SI units, 1 sigma.
struct ImuDatasheet {
  std::string name;
  double gyro_noise_density = 0.0;    // rad/s/sqrt(Hz)
  double accel_noise_density = 0.0;   // m/s^2/sqrt(Hz)
  double gyro_bias_stability = 0.0;   // rad/s, in-run
  double accel_bias_stability = 0.0;  // m/s^2, in-run
  double gyro_turn_on_bias = 0.0;     // rad/s, from one power-on to the next
  double accel_turn_on_bias = 0.0;    // m/s^2
  // The bias as a random walk that wanders by the in-run stability in 100 s (the time over
  // which datasheets quote it; Woodman, "An introduction to inertial navigation", 2007):
  // stability / sqrt(100 s), in rad/s^2/sqrt(Hz) and m/s^3/sqrt(Hz).
  double gyro_bias_random_walk() const;
  double accel_bias_random_walk() const;
};

// Analog Devices ADIS16448 (datasheet Rev. D): gyro noise density 0.0135 deg/s/sqrt(Hz), in-run
// bias stability 14.5 deg/h; accelerometer noise density 0.23 mg/sqrt(Hz), in-run bias
// stability 0.25 mg; turn-on bias 0.5 deg/s and 20 mg.
ImuDatasheet adis16448();

struct ImuOptions {
  ImuDatasheet datasheet = adis16448();
  // The IMU's pose in the LiDAR frame (the config's imu.extrinsic_*: R = Rz(yaw) Ry(pitch)
  // Rx(roll)): below the LiDAR in its mount, upside down, turned 90 deg and tilted 2.5 deg.
  std::array<double, 3> mount_rpy_deg{180.0, 2.5, 90.0};
  std::array<double, 3> mount_xyz_m{-0.12, 0.08, -0.18};
  double rate_hz = 200.0;
  double gravity = 9.81;  // m/s^2, down the world's z
  bool white_noise = true;
  bool bias_random_walk = true;
  bool turn_on_bias = true;

  Eigen::Isometry3d lidar_from_imu() const;
  // White noise per sample: density * sqrt(rate).
  double gyro_noise_sigma() const;
  double accel_noise_sigma() const;
};

// The errors drawn for one seed.
struct ImuErrors {
  Eigen::Vector3d gyro_turn_on_bias = Eigen::Vector3d::Zero();   // rad/s, IMU frame
  Eigen::Vector3d accel_turn_on_bias = Eigen::Vector3d::Zero();  // m/s^2
};

class ImuModel {
 public:
  // Throws std::invalid_argument on a rate that is not positive.
  ImuModel(const ImuOptions& options, uint64_t seed);

  // What an error-free IMU reads when the LiDAR moves as `lidar` (world kinematics, z up).
  ImuSample exact(const Kinematics& lidar, double stamp) const;
  // Samples at the options' rate from `from` to `to` (s, the trajectory's clock), with errors.
  std::vector<ImuSample> simulate(const SmoothTrajectory& trajectory, double from, double to) const;

  const ImuOptions& options() const { return options_; }
  const ImuErrors& errors() const { return errors_; }

 private:
  ImuOptions options_;
  uint64_t seed_;
  Eigen::Isometry3d lidar_from_imu_;
  ImuErrors errors_;
};

}  // namespace adaptive_lego_loam::sim
