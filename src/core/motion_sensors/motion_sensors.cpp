#include "adaptive_lego_loam/core/motion_sensors/motion_sensors.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "adaptive_lego_loam/core/common/rotations.h"

namespace adaptive_lego_loam {
namespace {

// The filter starts level by the mean specific force over this long before a scan.
constexpr double kLevellingWindow = 0.2;  // s
// Its velocity at the start: the LiDAR's last motion, to this; with none yet, unknown.
constexpr double kStartVelocitySigma = 2.0;  // m/s
// The filter starts after this many mapped motions in a row: the first pair of scans is
// registered from a search and the first sweep is not de-skewed.
constexpr int kStartAfterMotions = 3;
// A LiDAR motion this far from the filter's (RMS sigmas) is refused; this many in a row and the
// filter, not the LiDAR, is taken to be wrong: it starts again.
constexpr double kLidarGate = 20.0;
constexpr int kRefusalsBeforeRestart = 3;
constexpr double kUnknownVelocitySigma = 10.0;  // m/s
// The wheel's sideways and vertical speed of the base: 0 but for side slip and bumps.
constexpr double kSideSpeedSigma = 0.05;  // m/s
constexpr double kSideSpeedShare = 0.02;  // of the speed
// A wheel velocity further than this from the filter's (RMS sigmas) is slip; slips last about a
// second, and no scale is learned within one of one.
constexpr double kWheelGate = 5.0;
// The odometry's yaw rate is off by its track width's error besides its noise (a share of it).
constexpr double kYawRateShare = 0.05;
constexpr double kLongestSlip = 2.0;  // s
constexpr double kSlipQuiet = 1.0;    // s
// Without an IMU: how fast a vehicle's speed can change (m/s per s) since the last speed known
// before the wheel is taken to slip, beyond three of the odometry's sigmas.
constexpr double kMaxAcceleration = 5.0;
// The LiDAR's forward distance teaches the wheel its scale only when known this well; it is never
// taken to know it better than the floor.
constexpr double kScaleTeacherSigma = 0.1;    // m
constexpr double kScaleTeacherFloor = 0.005;  // m
constexpr double kSampleHistory = 1.0;        // s of samples kept before a scan

bool finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

// The filter's motion covariance [rotation, translation in the marked frame] as right
// perturbations of the motion: the translation turned into the motion's end frame.
Eigen::Matrix<double, 6, 6> right_perturbation_jacobian(const Eigen::Isometry3d& motion) {
  Eigen::Matrix<double, 6, 6> jacobian = Eigen::Matrix<double, 6, 6>::Identity();
  jacobian.bottomRightCorner<3, 3>() = motion.linear().transpose();
  return jacobian;
}

Matrix6d symmetric_inverse(const Matrix6d& m) {
  Eigen::SelfAdjointEigenSolver<Matrix6d> solver(0.5 * (m + m.transpose()));
  Eigen::Matrix<double, 6, 1> inverse = Eigen::Matrix<double, 6, 1>::Zero();
  const double largest = solver.eigenvalues().cwiseAbs().maxCoeff();
  for (int k = 0; k < 6; ++k)
    if (solver.eigenvalues()(k) > 1e-15 * largest) inverse(k) = 1.0 / solver.eigenvalues()(k);
  return solver.eigenvectors() * inverse.asDiagonal() * solver.eigenvectors().transpose();
}

}  // namespace

MotionSensors::MotionSensors(const Config& config, int sweep_steps)
    : imu_params_(config.imu),
      wheel_params_(config.wheel_odometry),
      sweep_steps_(sweep_steps),
      lidar_from_imu_(pose_from_rpy_xyz(config.imu.extrinsic_rpy_deg.data(),
                                        config.imu.extrinsic_xyz_m.data())),
      lidar_from_base_(pose_from_rpy_xyz(config.wheel_odometry.extrinsic_rpy_deg.data(),
                                         config.wheel_odometry.extrinsic_xyz_m.data())),
      imu_monitor_(config.imu.max_gap_s),
      wheel_monitor_(config.wheel_odometry.max_gap_s),
      filter_(config.imu) {}

std::optional<SampleFault> MotionSensors::add_imu(ImuSample sample) {
  sample.stamp += imu_params_.time_offset_s;
  const bool plausible = sample.angular_velocity.norm() <= imu_params_.max_angular_velocity &&
                         sample.linear_acceleration.norm() <= imu_params_.max_acceleration;
  const std::optional<SampleFault> fault = imu_monitor_.check(
      sample.stamp, finite(sample.angular_velocity) && finite(sample.linear_acceleration),
      plausible);
  status_.imu = imu_monitor_.status();
  if (!fault) imu_samples_.push_back(sample);
  return fault;
}

std::optional<SampleFault> MotionSensors::add_wheel(WheelOdometrySample sample) {
  sample.stamp += wheel_params_.time_offset_s;
  const bool plausible =
      std::fabs(sample.linear_velocity.x()) <= wheel_params_.max_speed &&
      std::fabs(sample.angular_velocity.z()) <= wheel_params_.max_yaw_rate_deg * M_PI / 180.0;
  const bool values_finite = finite(sample.linear_velocity) && finite(sample.angular_velocity) &&
                             std::isfinite(sample.linear_x_variance) &&
                             std::isfinite(sample.angular_z_variance);
  const std::optional<SampleFault> fault =
      wheel_monitor_.check(sample.stamp, values_finite, plausible);
  status_.wheel = wheel_monitor_.status();
  if (!fault) wheel_samples_.push_back(sample);
  return fault;
}

const MotionPrediction& MotionSensors::predict(double stamp, double sweep_period) {
  prediction_ = MotionPrediction();
  const bool imu_was_in_use = status_.imu_in_use;
  const bool wheel_was_in_use = status_.wheel_in_use;
  status_.imu_in_use = false;
  status_.wheel_in_use = false;
  wheel_motion_.reset();
  stamp_ = stamp;
  if (!active()) return prediction_;
  if (previous_stamp_ && filter_.initialized()) {
    if (samples_cover(imu_samples_, *previous_stamp_, stamp, imu_params_.max_gap_s)) {
      predict_with_filter(stamp, sweep_period);
    } else {
      filter_.reset();
      ++status_.imu_fallbacks;
    }
  } else if (imu_was_in_use) {
    ++status_.imu_fallbacks;
  }
  if (previous_stamp_ && !status_.imu_in_use && !wheel_samples_.empty()) {
    predict_with_wheel(stamp);
    if (!status_.wheel_in_use && wheel_was_in_use) ++status_.wheel_fallbacks;
  }
  status_.imu_scans += status_.imu_in_use;
  status_.wheel_scans += status_.wheel_in_use;
  interval_start_ = previous_stamp_;
  previous_stamp_ = stamp;
  drop_old_samples(stamp - std::max(kSampleHistory, 2.0 * sweep_period));
  return prediction_;
}

void MotionSensors::predict_with_filter(double stamp, double sweep_period) {
  const long slips_before = status_.wheel_slips;
  const double last_wheel_before = last_wheel_stamp_;
  propagate_to(stamp);
  status_.imu_in_use = true;
  status_.wheel_in_use =
      last_wheel_stamp_ > last_wheel_before && status_.wheel_slips == slips_before;
  // The wheel's scale is learned as without the IMU.
  if (status_.wheel_in_use) {
    wheel_motion_ = integrate_wheel(wheel_samples_, *previous_stamp_, stamp, wheel_params_);
  }
  if (recorded_.front().stamp <= stamp - sweep_period + 1e-9) {
    prediction_.sweep = sweep_motion(stamp, sweep_period);
  }
  const Eigen::Isometry3d imu_motion = filter_.motion_since_mark();
  const Eigen::Matrix<double, 6, 6> to_right = right_perturbation_jacobian(imu_motion);
  const Matrix6d imu_covariance = to_right * filter_.motion_covariance() * to_right.transpose();
  const Matrix6d to_lidar = adjoint(lidar_from_imu_);
  MotionPrior prior;
  prior.motion = motion_in_frame(imu_motion, lidar_from_imu_);
  prior.information = symmetric_inverse(to_lidar * imu_covariance * to_lidar.transpose());
  prior.from_imu = true;
  prior.from_wheel = status_.wheel_in_use;
  prediction_.motion = prior;
  GravityPrior gravity;
  gravity.up = lidar_from_imu_.linear() * filter_.up_in_imu();
  gravity.covariance =
      lidar_from_imu_.linear() * filter_.up_covariance() * lidar_from_imu_.linear().transpose();
  prediction_.gravity = gravity;
}

void MotionSensors::apply_wheel(const WheelOdometrySample& wheel, const Eigen::Vector3d& gyro) {
  last_wheel_stamp_ = wheel.stamp;
  const double scale = wheel_scale_.scale();
  const Eigen::Vector3d measured = scale * wheel.linear_velocity;
  const double speed = std::fabs(measured.x());
  const double reported = wheel.linear_x_variance > 0.0
                              ? wheel.linear_x_variance
                              : wheel_params_.speed_sigma * wheel_params_.speed_sigma;
  const double along = scale * scale * reported + std::pow(wheel_scale_.sigma() * speed, 2);
  const double side = std::pow(kSideSpeedSigma + kSideSpeedShare * speed, 2);
  // Forward and sideways: the base does not slide sideways; up and down it moves with the body on
  // its suspension, which the wheels do not see.
  const Eigen::Vector3d information(1.0 / along, 1.0 / side, 0.0);
  const Eigen::Isometry3d imu_from_base = lidar_from_imu_.inverse() * lidar_from_base_;
  // The base turns with the body about its vertical only: roll and pitch are the body's own.
  const Eigen::Vector3d base_up = imu_from_base.linear().col(2);
  const Eigen::Matrix3d yaw_only = base_up * base_up.transpose();
  // One wheel spinning or locked shows first in the yaw rate the odometry reports, against the
  // gyro's: a slip, whatever the forward speed says.
  const double body_yaw_rate = base_up.dot(gyro - filter_.state().gyro_bias);
  const double yaw_rate_sigma =
      std::sqrt(wheel.angular_z_variance > 0.0
                    ? wheel.angular_z_variance
                    : std::pow(wheel_params_.yaw_rate_sigma_deg * M_PI / 180.0, 2)) +
      kYawRateShare * std::fabs(body_yaw_rate);
  const bool yaw_agrees =
      std::fabs(wheel.angular_velocity.z() - body_yaw_rate) <= kWheelGate * yaw_rate_sigma;
  if (!yaw_agrees || !filter_.update_point_velocity(
                         measured, information.asDiagonal(), imu_from_base.translation(),
                         imu_from_base.linear(), gyro, yaw_only, kWheelGate)) {
    ++status_.wheel_slips;
    if (!refused_since_) refused_since_ = wheel.stamp;
    last_refusal_ = wheel.stamp;
    // A slip lasts a second or so; refused for longer, the filter is the one that is wrong (it
    // took the start of a slip for speed): it starts again from the LiDAR.
    if (wheel.stamp - *refused_since_ > kLongestSlip) {
      filter_.reset();
      refused_since_.reset();
    }
    return;
  }
  refused_since_.reset();
}

void MotionSensors::propagate_to(double stamp) {
  // One step of the filter, its motion added to the recorded path.
  const auto step = [&](double until, const Eigen::Vector3d& gyro, const Eigen::Vector3d& accel) {
    const Eigen::Isometry3d before = filter_.state().pose();
    filter_.propagate(until, gyro, accel);
    path_ = path_ * (before.inverse() * filter_.state().pose());
  };
  auto integrate = [&](double until, const Eigen::Vector3d& gyro, const Eigen::Vector3d& accel) {
    // Wheel velocities measured before `until` correct the state where they were measured.
    for (const WheelOdometrySample& wheel : wheel_samples_) {
      if (wheel.stamp <= last_wheel_stamp_ || wheel.stamp <= filter_.state().stamp) continue;
      if (wheel.stamp > until) break;
      step(wheel.stamp, gyro, accel);
      apply_wheel(wheel, gyro);
    }
    step(until, gyro, accel);
    record_pose();
  };
  for (const ImuSample& sample : imu_samples_) {
    if (sample.stamp <= filter_.state().stamp) continue;
    if (sample.stamp > stamp) break;
    // The mean rates over the step: the trapezoid of its two samples.
    const ImuSample& last = last_imu_ ? *last_imu_ : sample;
    integrate(sample.stamp, 0.5 * (last.angular_velocity + sample.angular_velocity),
              0.5 * (last.linear_acceleration + sample.linear_acceleration));
    last_imu_ = sample;
  }
  // The newest sample holds up to the scan.
  if (filter_.state().stamp < stamp && last_imu_) {
    integrate(stamp, last_imu_->angular_velocity, last_imu_->linear_acceleration);
  }
}

void MotionSensors::record_pose() {
  recorded_.push_back({filter_.state().stamp, path_});
}

Eigen::Isometry3d MotionSensors::recorded_pose(double stamp) const {
  const auto after =
      std::lower_bound(recorded_.begin(), recorded_.end(), stamp,
                       [](const TimedPose& pose, double t) { return pose.stamp < t; });
  if (after == recorded_.begin()) return recorded_.front().pose;
  if (after == recorded_.end()) return recorded_.back().pose;
  const TimedPose& a = *(after - 1);
  const TimedPose& b = *after;
  const double w = (stamp - a.stamp) / (b.stamp - a.stamp);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = a.pose.linear() *
                  rotation_exp(w * rotation_log(a.pose.linear().transpose() * b.pose.linear()));
  pose.translation() = (1.0 - w) * a.pose.translation() + w * b.pose.translation();
  return pose;
}

SweepMotion MotionSensors::sweep_motion(double stamp, double sweep_period) const {
  SweepMotion sweep;
  const Eigen::Isometry3d end_inverse = recorded_pose(stamp).inverse();
  for (int i = 0; i <= sweep_steps_; ++i) {
    const double t = stamp - sweep_period + sweep_period * i / sweep_steps_;
    sweep.end_from_fraction.push_back(
        motion_in_frame(end_inverse * recorded_pose(t), lidar_from_imu_));
  }
  return sweep;
}

void MotionSensors::predict_with_wheel(double stamp) {
  wheel_motion_ = integrate_wheel(wheel_samples_, *previous_stamp_, stamp, wheel_params_);
  if (!wheel_motion_) return;
  const double dt = stamp - *previous_stamp_;
  const double speed = wheel_scale_.scale() * wheel_motion_->distance / dt;
  if (reference_speed_ && dt > 0.0) {
    // Since the last speed known, the vehicle may have sped up or braked at most so much.
    const double since = stamp - reference_speed_->stamp;
    const double sigma = std::sqrt(wheel_motion_->distance_variance) / dt;
    if (std::fabs(speed - reference_speed_->speed) > kMaxAcceleration * since + 3.0 * sigma) {
      ++status_.wheel_slips;
      wheel_motion_.reset();
      return;
    }
  }
  prediction_.motion =
      wheel_prior(*wheel_motion_, wheel_scale_.scale(), wheel_scale_.sigma(), lidar_from_base_);
  prediction_.motion->from_wheel = true;
  status_.wheel_in_use = true;
}

void MotionSensors::update(const std::optional<Eigen::Isometry3d>& mapped_motion,
                           const Matrix6d& information, bool prior_held) {
  if (!active()) return;
  const std::optional<Eigen::Isometry3d>& lidar_motion = mapped_motion;
  if (status_.imu_in_use) {
    if (lidar_motion) {
      const Eigen::Isometry3d imu_motion =
          lidar_from_imu_.inverse() * *lidar_motion * lidar_from_imu_;
      const Matrix6d to_lidar = adjoint(lidar_from_imu_);
      const Eigen::Matrix<double, 6, 6> to_right = right_perturbation_jacobian(imu_motion);
      const Matrix6d imu_information = to_lidar.transpose() * information * to_lidar;
      if (filter_.update_motion(imu_motion, to_right.transpose() * imu_information * to_right,
                                kLidarGate)) {
        refusals_in_a_row_ = 0;
      } else {
        ++status_.lidar_rejections;
        ++refusals_in_a_row_;
      }
    }
    filter_.mark_scan();
    if (refusals_in_a_row_ >= kRefusalsBeforeRestart) {
      filter_.reset();
      refusals_in_a_row_ = 0;
    }
  } else if (!filter_.initialized() && lidar_motion && motions_in_a_row_ >= kStartAfterMotions &&
             interval_start_ &&
             samples_cover(imu_samples_, std::max(stamp_ - kLevellingWindow, *interval_start_),
                           stamp_, imu_params_.max_gap_s)) {
    // With the LiDAR's velocity known: it levels the filter in a turn and starts its velocity.
    start_filter(*lidar_motion);
  }
  motions_in_a_row_ = lidar_motion ? motions_in_a_row_ + 1 : 0;
  const double dt = interval_start_ ? stamp_ - *interval_start_ : 0.0;
  if (lidar_motion && dt > 0.0) {
    const bool after_slip = last_refusal_ && stamp_ - *last_refusal_ < kSlipQuiet;
    if (wheel_motion_ && motions_in_a_row_ > kStartAfterMotions && !prior_held && !after_slip) {
      learn_wheel_scale(*lidar_motion, information);
    }
    // The speed is known where the LiDAR measured the forward distance, or the wheel odometry
    // held it. Where neither did (a tunnel, the wheel refused) the mapped motion along the road
    // is the scene's false information: kept, the last known speed ages instead.
    if ((prior_held && wheel_motion_) ||
        forward_variance(information) < kScaleTeacherSigma * kScaleTeacherSigma) {
      const Eigen::Isometry3d base_motion =
          lidar_from_base_.inverse() * *lidar_motion * lidar_from_base_;
      reference_speed_ = TimedSpeed{stamp_, base_motion.translation().x() / dt};
    }
  }
  status_.gyro_bias = filter_.state().gyro_bias;
  status_.accel_bias = filter_.state().accel_bias;
  status_.wheel_scale = wheel_scale_.scale();
  status_.wheel_scale_sigma = wheel_scale_.sigma();
}

void MotionSensors::start_filter(const Eigen::Isometry3d& lidar_motion) {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), rate = Eigen::Vector3d::Zero();
  int count = 0;
  const double levelling_start = std::max(stamp_ - kLevellingWindow, *interval_start_);
  for (const ImuSample& sample : imu_samples_) {
    if (sample.stamp > stamp_) break;
    if (sample.stamp < levelling_start) continue;
    force += sample.linear_acceleration;
    rate += sample.angular_velocity;
    ++count;
    last_imu_ = sample;
  }
  if (count == 0) return;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  double velocity_sigma = kUnknownVelocitySigma;
  const double dt = interval_start_ ? stamp_ - *interval_start_ : 0.0;
  if (dt > 0.0) {
    // The LiDAR's mean velocity over the interval points along the chord, half the turn behind
    // its velocity at the end; the IMU's adds the lever arm's turn.
    const Eigen::Vector3d turn = rotation_log(lidar_motion.linear());
    const Eigen::Vector3d lidar_velocity =
        rotation_exp(-0.5 * turn) * lidar_motion.translation() / dt;
    const Eigen::Vector3d imu_velocity =
        lidar_velocity + (turn / dt).cross(lidar_from_imu_.translation());
    velocity = lidar_from_imu_.linear().transpose() * imu_velocity;
    velocity_sigma = kStartVelocitySigma;
  }
  // Gravity is the specific force less the turn's centripetal acceleration (a change of speed
  // cannot be told from a tilt yet).
  const Eigen::Vector3d gravity = force / count - (rate / count).cross(velocity);
  if (!recorded_.empty()) ++status_.imu_restarts;
  filter_.initialize(stamp_, gravity, velocity, velocity_sigma);
  recorded_.clear();
  path_ = filter_.state().pose();
  record_pose();
  last_wheel_stamp_ = std::max(last_wheel_stamp_, stamp_);
}

double MotionSensors::forward_variance(const Matrix6d& information) const {
  const Matrix6d to_lidar = adjoint(lidar_from_base_);
  const Matrix6d base_information = to_lidar.transpose() * information * to_lidar;
  return symmetric_inverse(base_information)(3, 3);
}

void MotionSensors::learn_wheel_scale(const Eigen::Isometry3d& lidar_motion,
                                      const Matrix6d& information) {
  const double variance = forward_variance(information);
  if (!(variance < kScaleTeacherSigma * kScaleTeacherSigma)) return;
  const Eigen::Isometry3d base_motion =
      lidar_from_base_.inverse() * lidar_motion * lidar_from_base_;
  wheel_scale_.add(wheel_motion_->distance, base_motion.translation().x(),
                   std::max(std::sqrt(variance), kScaleTeacherFloor));
}

void MotionSensors::drop_old_samples(double before) {
  while (imu_samples_.size() > 1 && imu_samples_[1].stamp < before)
    imu_samples_.pop_front();
  while (wheel_samples_.size() > 1 && wheel_samples_[1].stamp < before)
    wheel_samples_.pop_front();
  while (recorded_.size() > 1 && recorded_[1].stamp < before)
    recorded_.pop_front();
}

}  // namespace adaptive_lego_loam
