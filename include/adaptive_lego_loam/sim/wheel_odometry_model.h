#pragma once
// A car's wheel odometry along the smooth trajectory's chassis (without a rough road's shake), as
// a differential-drive odometry reports it: the base frame's (the rear axle's centre on the
// ground) forward speed and yaw rate from the two rear wheels' speeds, with a scale error, a
// track-width error, white noise and slip events, sideways and vertical speed 0 whatever the
// vehicle does.

#include <array>
#include <cstdint>
#include <vector>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"
#include "adaptive_lego_loam/sim/smooth_trajectory.h"

namespace adaptive_lego_loam::sim {

struct WheelOdometryOptions {
  // The base frame's pose in the LiDAR frame with the body at rest (the config's
  // wheel_odometry.extrinsic_*): the rear axle's centre on the ground below the LiDAR (z = -sensor
  // height). The simulated vehicle's path is the LiDAR's, heading along its tangent: the point
  // that does not slide sideways in a turn is the one below the LiDAR, so the rear axle is there.
  // The base is on the chassis; on a rough road the LiDAR shakes with the body above it.
  std::array<double, 3> mount_rpy_deg{0.0, 0.0, 0.0};
  std::array<double, 3> mount_xyz_m{0.0, 0.0, -1.73};
  double rate_hz = 50.0;
  double track_width_m = 1.6;       // between the rear wheels
  double wheel_speed_noise = 0.03;  // m/s per wheel, white
  // Per seed: the wheels' scale error |s| in [min, max] either sign (tyre radius, pressure,
  // load), the track width the odometry assumes off by up to +-max_track_error, and a rate of
  // slips per km in [min, max].
  double min_scale_error = 0.01, max_scale_error = 0.03;
  double max_track_error = 0.02;
  double min_slips_per_km = 1.0, max_slips_per_km = 4.0;
  // A slip: a driven wheel spins on a wet patch for `duration` s, its speed over the true one by
  // up to `excess` (a raised cosine).
  double min_slip_duration_s = 0.6, max_slip_duration_s = 1.5;
  double min_slip_excess = 0.2, max_slip_excess = 0.6;
  // What the odometry reports as its variances: fixed, as a driver's configured covariance.
  double reported_speed_sigma = 0.05;     // m/s
  double reported_yaw_rate_sigma = 0.02;  // rad/s
  bool scale_error = true;
  bool noise = true;
  bool slips = true;

  Eigen::Isometry3d lidar_from_base() const;
};

struct SlipEvent {
  double start_s = 0.0;  // on the trajectory's clock
  double duration_s = 0.0;
  double excess = 0.0;  // at the peak: the wheel turns (1 + excess) times as fast as it rolls
  bool left_wheel = true;
};

// The errors drawn for one seed (the slips' times depend on the drive: WheelOdometryRun).
struct WheelOdometryErrors {
  double scale_error = 0.0;        // reported / true speed - 1
  double track_width_error = 0.0;  // assumed / true track width - 1
  double slips_per_km = 0.0;
};

struct WheelOdometryRun {
  std::vector<WheelOdometrySample> samples;
  std::vector<SlipEvent> slips;
};

class WheelOdometryModel {
 public:
  // Throws std::invalid_argument on a rate or track width that is not positive.
  WheelOdometryModel(const WheelOdometryOptions& options, uint64_t seed);

  // Samples at the options' rate from `from` to `to` (s), with errors.
  WheelOdometryRun simulate(const SmoothTrajectory& trajectory, double from, double to) const;

  const WheelOdometryOptions& options() const { return options_; }
  const WheelOdometryErrors& errors() const { return errors_; }

 private:
  WheelOdometryOptions options_;
  uint64_t seed_;
  WheelOdometryErrors errors_;
};

// The base frame's pose from the first sample's on, as a driver integrates its twist into
// nav_msgs/Odometry's pose: planar, each sample's speed and yaw rate held until the next, at the
// interval's middle heading. Samples with a non-finite value or a stamp not after the last are
// skipped.
std::vector<Eigen::Isometry3d> integrate_odometry(const std::vector<WheelOdometrySample>& samples);

}  // namespace adaptive_lego_loam::sim
