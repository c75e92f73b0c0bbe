#include "adaptive_lego_loam/sim/imu_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/sim/random.h"

namespace adaptive_lego_loam::sim {
namespace {

constexpr uint64_t kTurnOnStream = 0x494D55424941ull;  // "IMUBIA"
constexpr uint64_t kNoiseStream = 0x494D554E4F49ull;   // "IMUNOI"
constexpr double kStandardGravity = 9.80665;           // what datasheets mean by 1 g
constexpr double kDegree = M_PI / 180.0;
constexpr double kBiasStabilityPeriod = 100.0;  // s

Eigen::Vector3d normal_vector(Rng& rng) {
  const double x = rng.standard_normal(), y = rng.standard_normal();
  return Eigen::Vector3d(x, y, rng.standard_normal());
}

// Within +-3 sigma, as a datasheet's 1-sigma figure covers nearly every part.
Eigen::Vector3d turn_on_bias(Rng& rng, double sigma) {
  return (sigma * normal_vector(rng)).cwiseMax(-3.0 * sigma).cwiseMin(3.0 * sigma);
}

}  // namespace

double ImuDatasheet::gyro_bias_random_walk() const {
  return gyro_bias_stability / std::sqrt(kBiasStabilityPeriod);
}

double ImuDatasheet::accel_bias_random_walk() const {
  return accel_bias_stability / std::sqrt(kBiasStabilityPeriod);
}

ImuDatasheet adis16448() {
  ImuDatasheet d;
  d.name = "Analog Devices ADIS16448";
  d.gyro_noise_density = 0.0135 * kDegree;
  d.accel_noise_density = 0.23e-3 * kStandardGravity;
  d.gyro_bias_stability = 14.5 * kDegree / 3600.0;
  d.accel_bias_stability = 0.25e-3 * kStandardGravity;
  d.gyro_turn_on_bias = 0.5 * kDegree;
  d.accel_turn_on_bias = 20e-3 * kStandardGravity;
  return d;
}

Eigen::Isometry3d ImuOptions::lidar_from_imu() const {
  return pose_from_rpy_xyz(mount_rpy_deg.data(), mount_xyz_m.data());
}

double ImuOptions::gyro_noise_sigma() const {
  return datasheet.gyro_noise_density * std::sqrt(rate_hz);
}

double ImuOptions::accel_noise_sigma() const {
  return datasheet.accel_noise_density * std::sqrt(rate_hz);
}

ImuModel::ImuModel(const ImuOptions& options, uint64_t seed)
    : options_(options), seed_(seed), lidar_from_imu_(options.lidar_from_imu()) {
  if (!(options_.rate_hz > 0.0)) throw std::invalid_argument("IMU rate must be positive");
  Rng rng(derive_seed(seed, kTurnOnStream));
  const Eigen::Vector3d gyro = turn_on_bias(rng, options_.datasheet.gyro_turn_on_bias);
  const Eigen::Vector3d accel = turn_on_bias(rng, options_.datasheet.accel_turn_on_bias);
  if (options_.turn_on_bias) errors_ = {gyro, accel};
}

ImuSample ImuModel::exact(const Kinematics& lidar, double stamp) const {
  const Kinematics imu = mounted(lidar, lidar_from_imu_);
  ImuSample sample;
  sample.stamp = stamp;
  sample.angular_velocity = imu.angular_velocity;
  const Eigen::Vector3d gravity(0.0, 0.0, -options_.gravity);
  sample.linear_acceleration = imu.pose.linear().transpose() * (imu.acceleration - gravity);
  return sample;
}

std::vector<ImuSample> ImuModel::simulate(const SmoothTrajectory& trajectory, double from,
                                          double to) const {
  const double dt = 1.0 / options_.rate_hz;
  const double gyro_noise = options_.white_noise ? options_.gyro_noise_sigma() : 0.0;
  const double accel_noise = options_.white_noise ? options_.accel_noise_sigma() : 0.0;
  const double gyro_walk =
      options_.bias_random_walk ? options_.datasheet.gyro_bias_random_walk() * std::sqrt(dt) : 0.0;
  const double accel_walk =
      options_.bias_random_walk ? options_.datasheet.accel_bias_random_walk() * std::sqrt(dt) : 0.0;
  Eigen::Vector3d gyro_bias = errors_.gyro_turn_on_bias;
  Eigen::Vector3d accel_bias = errors_.accel_turn_on_bias;
  // Every number is drawn whichever errors are on, so that turning one off leaves the others.
  Rng rng(derive_seed(seed_, kNoiseStream));
  std::vector<ImuSample> samples;
  for (double time : sample_times(from, to, options_.rate_hz)) {
    ImuSample sample = exact(trajectory.motion(time), time);
    sample.angular_velocity += gyro_bias + gyro_noise * normal_vector(rng);
    sample.linear_acceleration += accel_bias + accel_noise * normal_vector(rng);
    samples.push_back(sample);
    gyro_bias += gyro_walk * normal_vector(rng);
    accel_bias += accel_walk * normal_vector(rng);
  }
  return samples;
}

}  // namespace adaptive_lego_loam::sim
