#pragma once
// A loosely coupled error-state Kalman filter of the IMU (docs/METHOD.md, "Motion sensors"): the
// gyro and accelerometer integrated between scans, corrected by the LiDAR's relative motion
// between consecutive scans (stochastic cloning of the previous scan's pose) and by the wheel
// odometry's body velocity. It estimates the attitude against gravity, the velocity and both
// biases; its world frame is level (z up), with the yaw and origin of the IMU at the start.

#include <Eigen/Geometry>

#include "adaptive_lego_loam/core/common/params.h"

namespace adaptive_lego_loam {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// The filter's nominal state: the IMU in the world frame.
struct InertialState {
  double stamp = 0.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  Eigen::Isometry3d pose() const;
};

class InertialFilter {
 public:
  // The error state: attitude (body frame), velocity, position, gyro bias, accelerometer bias,
  // then the clone of the attitude and position at the last scan.
  static constexpr int kAttitude = 0, kVelocity = 3, kPosition = 6, kGyroBias = 9, kAccelBias = 12,
                       kCloneAttitude = 15, kClonePosition = 18, kSize = 21;
  using Covariance = Eigen::Matrix<double, kSize, kSize>;

  explicit InertialFilter(const ImuParams& params);

  bool initialized() const { return initialized_; }
  // Starts at `stamp`, level by `specific_force` (a mean accelerometer reading, IMU frame, taken
  // as gravity alone), yaw 0, moving at `body_velocity` (IMU frame) known to `velocity_sigma`
  // (m/s). Biases keep their estimates (zero at first) and their uncertainty. Also marks a scan.
  void initialize(double stamp, const Eigen::Vector3d& specific_force,
                  const Eigen::Vector3d& body_velocity, double velocity_sigma);
  // Loses the state (a gap in the IMU's samples); the biases and their uncertainty are kept.
  void reset() { initialized_ = false; }

  // Integrates from the current stamp to `stamp` with the mean angular velocity and specific
  // force over the step (IMU frame, raw: the biases are removed here).
  void propagate(double stamp, const Eigen::Vector3d& gyro, const Eigen::Vector3d& accel);

  // The IMU's motion since the last marked scan (its pose then, inverse, times its pose now) and
  // its covariance: [rotation vector (rad), translation (m)] in the IMU frame of the marked scan.
  Eigen::Isometry3d motion_since_mark() const;
  Matrix6d motion_covariance() const;
  // Corrects the state with a measured motion since the last marked scan (the same
  // parameterisation) of `information` (6 x 6, symmetric, possibly singular: directions without
  // information are not corrected). Returns false when the measurement is rejected (its
  // Mahalanobis distance beyond `gate` sigmas in the measured directions).
  bool update_motion(const Eigen::Isometry3d& measured, const Matrix6d& information,
                     double gate = 0.0);
  // Corrects the state with the measured velocity of a point attached to the IMU (at `lever_arm`,
  // IMU frame), expressed in a frame of orientation `frame_rotation` relative to the IMU (the wheel
  // odometry's base): the IMU's velocity plus the turn about `turn_axes` (a projection of the
  // angular velocity: a body rolls and pitches on its suspension without moving its wheels)
  // times the lever arm. `information` 3 x 3, possibly singular. Returns false when rejected by
  // the gate (0: none).
  bool update_point_velocity(const Eigen::Vector3d& measured, const Eigen::Matrix3d& information,
                             const Eigen::Vector3d& lever_arm,
                             const Eigen::Matrix3d& frame_rotation, const Eigen::Vector3d& gyro,
                             const Eigen::Matrix3d& turn_axes, double gate = 0.0);
  // Makes the current pose the marked scan's.
  void mark_scan();

  const InertialState& state() const { return state_; }
  const Covariance& covariance() const { return covariance_; }
  // Gravity's up direction in the IMU frame and its covariance.
  Eigen::Vector3d up_in_imu() const;
  Eigen::Matrix3d up_covariance() const;

 private:
  // The Kalman update of a linearised measurement: `residual` = z - h(x), `jacobian` of h over the
  // error state, `information` of z. Returns false when gated out.
  template <int Rows>
  bool correct(const Eigen::Matrix<double, Rows, 1>& residual,
               const Eigen::Matrix<double, Rows, kSize>& jacobian,
               const Eigen::Matrix<double, Rows, Rows>& information, double gate);
  void inject(const Eigen::Matrix<double, kSize, 1>& error);

  ImuParams params_;
  bool initialized_ = false;
  InertialState state_;
  Eigen::Matrix3d clone_rotation_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d clone_position_ = Eigen::Vector3d::Zero();
  Covariance covariance_ = Covariance::Zero();
};

}  // namespace adaptive_lego_loam
