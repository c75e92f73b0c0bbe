#include "adaptive_lego_loam/core/motion_sensors/inertial_filter.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "adaptive_lego_loam/core/common/rotations.h"

namespace adaptive_lego_loam {
namespace {

using Matrix15d = Eigen::Matrix<double, 15, 15>;

// The error-state indices of the pose the motion is measured between: now and at the mark.
constexpr int kPoseNow[6] = {0, 1, 2, 6, 7, 8};

// 1-sigma of the attitude about gravity at the start: the world's yaw is the IMU's at the start
// by definition, so nothing measures it; a small value keeps the covariance well conditioned.
constexpr double kStartYawSigma = 1e-3;    // rad
constexpr double kStartTiltSigma = 0.035;  // rad: a vehicle accelerating at 0.35 m/s^2

}  // namespace

Eigen::Isometry3d InertialState::pose() const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = position;
  return pose;
}

InertialFilter::InertialFilter(const ImuParams& params) : params_(params) {
  covariance_.block<3, 3>(kGyroBias, kGyroBias) =
      Eigen::Matrix3d::Identity() * params.gyro_bias_sigma * params.gyro_bias_sigma;
  covariance_.block<3, 3>(kAccelBias, kAccelBias) =
      Eigen::Matrix3d::Identity() * params.accel_bias_sigma * params.accel_bias_sigma;
}

void InertialFilter::initialize(double stamp, const Eigen::Vector3d& specific_force,
                                const Eigen::Vector3d& body_velocity, double velocity_sigma) {
  const Eigen::Matrix3d bias_gyro = covariance_.block<3, 3>(kGyroBias, kGyroBias);
  const Eigen::Matrix3d bias_accel = covariance_.block<3, 3>(kAccelBias, kAccelBias);
  state_.stamp = stamp;
  // The least rotation that turns the measured up onto the world's z: yaw 0.
  state_.rotation =
      Eigen::Quaterniond::FromTwoVectors(specific_force.normalized(), Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  state_.position.setZero();
  state_.velocity = state_.rotation * body_velocity;
  covariance_.setZero();
  // Tilt about the body's horizontal axes, yaw about its up.
  const Eigen::Vector3d up = state_.rotation.transpose() * Eigen::Vector3d::UnitZ();
  covariance_.block<3, 3>(kAttitude, kAttitude) =
      kStartTiltSigma * kStartTiltSigma * (Eigen::Matrix3d::Identity() - up * up.transpose()) +
      kStartYawSigma * kStartYawSigma * up * up.transpose();
  covariance_.block<3, 3>(kVelocity, kVelocity) =
      Eigen::Matrix3d::Identity() * velocity_sigma * velocity_sigma;
  covariance_.block<3, 3>(kGyroBias, kGyroBias) = bias_gyro;
  covariance_.block<3, 3>(kAccelBias, kAccelBias) = bias_accel;
  initialized_ = true;
  mark_scan();
}

void InertialFilter::propagate(double stamp, const Eigen::Vector3d& gyro,
                               const Eigen::Vector3d& accel) {
  const double dt = stamp - state_.stamp;
  if (!(dt > 0.0)) return;
  const Eigen::Vector3d rate = gyro - state_.gyro_bias;
  const Eigen::Vector3d force = accel - state_.accel_bias;
  const Eigen::Matrix3d turn = rotation_exp(rate * dt);
  const Eigen::Matrix3d start = state_.rotation;
  const Eigen::Matrix3d end = start * turn;
  const Eigen::Vector3d gravity(0.0, 0.0, -params_.gravity);
  const Eigen::Vector3d acceleration = 0.5 * (start + end) * force + gravity;
  state_.position += state_.velocity * dt + 0.5 * acceleration * dt * dt;
  state_.velocity += acceleration * dt;
  state_.rotation = end;
  state_.stamp = stamp;

  Matrix15d transition = Matrix15d::Identity();
  transition.block<3, 3>(kAttitude, kAttitude) = turn.transpose();
  transition.block<3, 3>(kAttitude, kGyroBias) = -Eigen::Matrix3d::Identity() * dt;
  transition.block<3, 3>(kVelocity, kAttitude) = -start * skew(force) * dt;
  transition.block<3, 3>(kVelocity, kAccelBias) = -start * dt;
  transition.block<3, 3>(kPosition, kVelocity) = Eigen::Matrix3d::Identity() * dt;
  Matrix15d noise = Matrix15d::Zero();
  const auto square = [](double x) { return x * x; };
  noise.block<3, 3>(kAttitude, kAttitude)
      .diagonal()
      .setConstant(square(params_.gyro_noise_density) * dt);
  noise.block<3, 3>(kVelocity, kVelocity)
      .diagonal()
      .setConstant(square(params_.accel_noise_density) * dt);
  noise.block<3, 3>(kGyroBias, kGyroBias)
      .diagonal()
      .setConstant(square(params_.gyro_bias_random_walk) * dt);
  noise.block<3, 3>(kAccelBias, kAccelBias)
      .diagonal()
      .setConstant(square(params_.accel_bias_random_walk) * dt);
  const Matrix15d main = covariance_.topLeftCorner<15, 15>();
  covariance_.topLeftCorner<15, 15>() = transition * main * transition.transpose() + noise;
  const Eigen::Matrix<double, 15, 6> cross = covariance_.topRightCorner<15, 6>();
  covariance_.topRightCorner<15, 6>() = transition * cross;
  covariance_.bottomLeftCorner<6, 15>() = covariance_.topRightCorner<15, 6>().transpose();
}

Eigen::Isometry3d InertialFilter::motion_since_mark() const {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = clone_rotation_.transpose() * state_.rotation;
  motion.translation() = clone_rotation_.transpose() * (state_.position - clone_position_);
  return motion;
}

namespace {

// The Jacobian of the motion since the mark, [log(R_c^T R), R_c^T (p - p_c)], over the error
// state (right perturbations of both attitudes).
Eigen::Matrix<double, 6, InertialFilter::kSize> motion_jacobian(
    const Eigen::Matrix3d& clone_rotation, const Eigen::Isometry3d& motion) {
  using F = InertialFilter;
  Eigen::Matrix<double, 6, F::kSize> jacobian = Eigen::Matrix<double, 6, F::kSize>::Zero();
  jacobian.block<3, 3>(0, F::kAttitude) = Eigen::Matrix3d::Identity();
  jacobian.block<3, 3>(0, F::kCloneAttitude) = -motion.linear().transpose();
  jacobian.block<3, 3>(3, F::kPosition) = clone_rotation.transpose();
  jacobian.block<3, 3>(3, F::kClonePosition) = -clone_rotation.transpose();
  jacobian.block<3, 3>(3, F::kCloneAttitude) = skew(motion.translation());
  return jacobian;
}

}  // namespace

Matrix6d InertialFilter::motion_covariance() const {
  const Eigen::Matrix<double, 6, kSize> jacobian =
      motion_jacobian(clone_rotation_, motion_since_mark());
  return jacobian * covariance_ * jacobian.transpose();
}

template <int Rows>
bool InertialFilter::correct(const Eigen::Matrix<double, Rows, 1>& residual,
                             const Eigen::Matrix<double, Rows, kSize>& jacobian,
                             const Eigen::Matrix<double, Rows, Rows>& information, double gate) {
  // Only the measured directions: the information's eigenvectors with a non-negligible
  // eigenvalue, each a measurement of variance 1 / eigenvalue.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, Rows, Rows>> solver(information);
  const double largest = solver.eigenvalues().maxCoeff();
  if (!(largest > 0.0)) return true;
  std::vector<int> kept;
  for (int k = 0; k < Rows; ++k)
    if (solver.eigenvalues()(k) > 1e-9 * largest) kept.push_back(k);
  const int m = static_cast<int>(kept.size());
  Eigen::MatrixXd directions(Rows, m);
  Eigen::VectorXd variances(m);
  for (int i = 0; i < m; ++i) {
    directions.col(i) = solver.eigenvectors().col(kept[i]);
    variances(i) = 1.0 / solver.eigenvalues()(kept[i]);
  }
  const Eigen::VectorXd r = directions.transpose() * residual;
  const Eigen::MatrixXd h = directions.transpose() * jacobian;
  Eigen::MatrixXd innovation = h * covariance_ * h.transpose();
  innovation.diagonal() += variances;
  const Eigen::MatrixXd innovation_inverse = innovation.inverse();
  if (gate > 0.0 && r.dot(innovation_inverse * r) > gate * gate * m) return false;
  const Eigen::MatrixXd gain = covariance_ * h.transpose() * innovation_inverse;
  const Eigen::Matrix<double, kSize, 1> error = gain * r;
  const Eigen::MatrixXd keep = Eigen::MatrixXd::Identity(kSize, kSize) - gain * h;
  // Joseph's form: stays symmetric and positive.
  covariance_ =
      keep * covariance_ * keep.transpose() + gain * variances.asDiagonal() * gain.transpose();
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
  inject(error);
  return true;
}

void InertialFilter::inject(const Eigen::Matrix<double, kSize, 1>& error) {
  state_.rotation = state_.rotation * rotation_exp(error.segment<3>(kAttitude));
  state_.velocity += error.segment<3>(kVelocity);
  state_.position += error.segment<3>(kPosition);
  // A bias beyond three of its start-up sigmas is not the sensor's: what was taken for it is
  // another error (a LiDAR that measured a motion it could not see).
  const auto bounded = [](const Eigen::Vector3d& bias, double sigma) {
    return bias.cwiseMax(-3.0 * sigma).cwiseMin(3.0 * sigma).eval();
  };
  state_.gyro_bias =
      bounded(state_.gyro_bias + error.segment<3>(kGyroBias), params_.gyro_bias_sigma);
  state_.accel_bias =
      bounded(state_.accel_bias + error.segment<3>(kAccelBias), params_.accel_bias_sigma);
  clone_rotation_ = clone_rotation_ * rotation_exp(error.segment<3>(kCloneAttitude));
  clone_position_ += error.segment<3>(kClonePosition);
}

bool InertialFilter::update_motion(const Eigen::Isometry3d& measured, const Matrix6d& information,
                                   double gate) {
  const Eigen::Isometry3d predicted = motion_since_mark();
  Vector6d residual;
  residual.head<3>() = rotation_log(predicted.linear().transpose() * measured.linear());
  residual.tail<3>() = measured.translation() - predicted.translation();
  return correct<6>(residual, motion_jacobian(clone_rotation_, predicted), information, gate);
}

bool InertialFilter::update_point_velocity(const Eigen::Vector3d& measured,
                                           const Eigen::Matrix3d& information,
                                           const Eigen::Vector3d& lever_arm,
                                           const Eigen::Matrix3d& frame_rotation,
                                           const Eigen::Vector3d& gyro,
                                           const Eigen::Matrix3d& turn_axes, double gate) {
  const Eigen::Vector3d rate = turn_axes * (gyro - state_.gyro_bias);
  const Eigen::Vector3d body_velocity = state_.rotation.transpose() * state_.velocity;
  const Eigen::Vector3d predicted =
      frame_rotation.transpose() * (body_velocity + rate.cross(lever_arm));
  Eigen::Matrix<double, 3, kSize> jacobian = Eigen::Matrix<double, 3, kSize>::Zero();
  jacobian.block<3, 3>(0, kVelocity) = frame_rotation.transpose() * state_.rotation.transpose();
  jacobian.block<3, 3>(0, kAttitude) = frame_rotation.transpose() * skew(body_velocity);
  jacobian.block<3, 3>(0, kGyroBias) = frame_rotation.transpose() * skew(lever_arm) * turn_axes;
  return correct<3>(measured - predicted, jacobian, information, gate);
}

void InertialFilter::mark_scan() {
  clone_rotation_ = state_.rotation;
  clone_position_ = state_.position;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < kSize; ++j) {
      const int source_j = j >= kCloneAttitude ? kPoseNow[j - kCloneAttitude] : j;
      covariance_(kCloneAttitude + i, j) = covariance_(kPoseNow[i], source_j);
    }
  }
  for (int i = 0; i < kSize; ++i)
    for (int j = 0; j < 6; ++j)
      covariance_(i, kCloneAttitude + j) = covariance_(kCloneAttitude + j, i);
}

Eigen::Vector3d InertialFilter::up_in_imu() const {
  return state_.rotation.transpose() * Eigen::Vector3d::UnitZ();
}

Eigen::Matrix3d InertialFilter::up_covariance() const {
  const Eigen::Matrix3d turn = skew(up_in_imu());
  return turn * covariance_.block<3, 3>(kAttitude, kAttitude) * turn.transpose();
}

}  // namespace adaptive_lego_loam
