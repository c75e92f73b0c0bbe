#include "adaptive_lego_loam/sim/wheel_odometry_model.h"

#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/sim/random.h"

namespace adaptive_lego_loam::sim {
namespace {

constexpr uint64_t kErrorStream = 0x574845454C45ull;  // "WHEELE"
constexpr uint64_t kSlipStream = 0x574845454C53ull;   // "WHEELS"
constexpr uint64_t kNoiseStream = 0x574845454C4Eull;  // "WHEELN"

// The true forward speed and yaw rate of the base at each time: it is on the chassis, which the
// wheels roll with, not on the body shaking above it.
struct BaseMotion {
  double time, speed, yaw_rate;
};

std::vector<BaseMotion> base_motions(const SmoothTrajectory& trajectory,
                                     const Eigen::Isometry3d& lidar_from_base,
                                     const std::vector<double>& times) {
  std::vector<BaseMotion> motions;
  for (double time : times) {
    const Kinematics base = mounted(trajectory.unshaken_motion(time), lidar_from_base);
    motions.push_back({time, base.body_velocity().x(), base.angular_velocity.z()});
  }
  return motions;
}

// Slips at distances along the drive a Poisson process of `per_km` apart, each at least its
// duration after the last one's start.
std::vector<SlipEvent> draw_slips(const WheelOdometryOptions& o, double per_km,
                                  const std::vector<BaseMotion>& motions, Rng& rng) {
  std::vector<SlipEvent> slips;
  if (per_km <= 0.0 || motions.size() < 2) return slips;
  const double mean_gap_m = 1000.0 / per_km;
  double next_m = -mean_gap_m * std::log(1.0 - rng.uniform());
  double driven_m = 0.0;
  for (std::size_t k = 1; k < motions.size(); ++k) {
    driven_m += std::abs(motions[k - 1].speed) * (motions[k].time - motions[k - 1].time);
    if (driven_m < next_m) continue;
    SlipEvent slip;
    slip.start_s = motions[k].time;
    slip.duration_s = rng.uniform(o.min_slip_duration_s, o.max_slip_duration_s);
    slip.excess = rng.uniform(o.min_slip_excess, o.max_slip_excess);
    slip.left_wheel = rng.chance(0.5);
    if (slips.empty() || slip.start_s >= slips.back().start_s + slips.back().duration_s)
      slips.push_back(slip);
    next_m += -mean_gap_m * std::log(1.0 - rng.uniform());
  }
  return slips;
}

// How much faster than it rolls a wheel turns at `time`: 1 outside a slip.
double spin(const std::vector<SlipEvent>& slips, double time, bool left_wheel) {
  for (const SlipEvent& slip : slips) {
    const double into = (time - slip.start_s) / slip.duration_s;
    if (slip.left_wheel == left_wheel && into > 0.0 && into < 1.0) {
      const double rise = std::sin(M_PI * into);
      return 1.0 + slip.excess * rise * rise;
    }
  }
  return 1.0;
}

}  // namespace

Eigen::Isometry3d WheelOdometryOptions::lidar_from_base() const {
  return pose_from_rpy_xyz(mount_rpy_deg.data(), mount_xyz_m.data());
}

WheelOdometryModel::WheelOdometryModel(const WheelOdometryOptions& options, uint64_t seed)
    : options_(options), seed_(seed) {
  if (!(options_.rate_hz > 0.0 && options_.track_width_m > 0.0))
    throw std::invalid_argument("wheel odometry: rate and track width must be positive");
  Rng rng(derive_seed(seed, kErrorStream));
  const double scale = rng.sign() * rng.uniform(options_.min_scale_error, options_.max_scale_error);
  const double track = rng.uniform(-options_.max_track_error, options_.max_track_error);
  const double slips = rng.uniform(options_.min_slips_per_km, options_.max_slips_per_km);
  if (options_.scale_error) {
    errors_.scale_error = scale;
    errors_.track_width_error = track;
  }
  if (options_.slips) errors_.slips_per_km = slips;
}

WheelOdometryRun WheelOdometryModel::simulate(const SmoothTrajectory& trajectory, double from,
                                              double to) const {
  const std::vector<BaseMotion> motions = base_motions(trajectory, options_.lidar_from_base(),
                                                       sample_times(from, to, options_.rate_hz));
  Rng slip_rng(derive_seed(seed_, kSlipStream));
  WheelOdometryRun run;
  run.slips = draw_slips(options_, errors_.slips_per_km, motions, slip_rng);
  const double half_track = 0.5 * options_.track_width_m;
  const double assumed_track = options_.track_width_m * (1.0 + errors_.track_width_error);
  const double scale = 1.0 + errors_.scale_error;
  const double noise = options_.noise ? options_.wheel_speed_noise : 0.0;
  Rng noise_rng(derive_seed(seed_, kNoiseStream));
  for (const BaseMotion& m : motions) {
    const double left_noise = noise_rng.standard_normal();
    const double right_noise = noise_rng.standard_normal();
    const double left =
        scale * (m.speed - half_track * m.yaw_rate) * spin(run.slips, m.time, true) +
        noise * left_noise;
    const double right =
        scale * (m.speed + half_track * m.yaw_rate) * spin(run.slips, m.time, false) +
        noise * right_noise;
    WheelOdometrySample sample;
    sample.stamp = m.time;
    sample.linear_velocity.x() = 0.5 * (left + right);
    sample.angular_velocity.z() = (right - left) / assumed_track;
    sample.linear_x_variance = options_.reported_speed_sigma * options_.reported_speed_sigma;
    sample.angular_z_variance = options_.reported_yaw_rate_sigma * options_.reported_yaw_rate_sigma;
    run.samples.push_back(sample);
  }
  return run;
}

std::vector<Eigen::Isometry3d> integrate_odometry(const std::vector<WheelOdometrySample>& samples) {
  std::vector<Eigen::Isometry3d> poses;
  double x = 0.0, y = 0.0, heading = 0.0;
  const WheelOdometrySample* held = nullptr;
  for (const WheelOdometrySample& sample : samples) {
    const bool finite = std::isfinite(sample.stamp) && sample.linear_velocity.allFinite() &&
                        sample.angular_velocity.allFinite();
    if (held && finite && sample.stamp > held->stamp) {
      const double dt = sample.stamp - held->stamp;
      const double turn = held->angular_velocity.z() * dt;
      const double middle = heading + 0.5 * turn;
      x += held->linear_velocity.x() * dt * std::cos(middle);
      y += held->linear_velocity.x() * dt * std::sin(middle);
      heading += turn;
    }
    if (finite && (!held || sample.stamp > held->stamp)) held = &sample;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(x, y, 0.0);
    pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace adaptive_lego_loam::sim
