#pragma once
// What the motion sensors tell the LiDAR stages about one scan: how the sensor moved along its
// sweep (de-skewing), how it moved since the previous scan (the guess and a prior), and where
// gravity points (the attitude prior). All in the LiDAR frame.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace adaptive_lego_loam {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The sensor's pose at evenly spaced fractions of its sweep, from its start (0) to its end (1),
// each relative to the pose at the sweep's end (end_from_fraction.back() is the identity).
struct SweepMotion {
  std::vector<Eigen::Isometry3d> end_from_fraction;
  // The pose at fraction `s` in [0, 1], interpolated between the samples.
  Eigen::Isometry3d at(double s) const;
};

// Where motion sensors say the sensor moved since the previous scan: the motion (the pose now in
// the frame of the previous scan) and its information over [rotation vector, translation] of a
// right perturbation (motion * exp(xi)), 1/rad^2 and 1/m^2; possibly singular (a wheel odometry
// says nothing of roll or pitch).
struct MotionPrior {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  Matrix6d information = Matrix6d::Zero();
  bool from_imu = false;    // the IMU's filter measured it ...
  bool from_wheel = false;  // ... with, or this alone, the wheel odometry
};

// Gravity's up direction in the sensor frame, and the covariance of that unit vector.
struct GravityPrior {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

struct MotionPrediction {
  std::optional<SweepMotion> sweep;     // IMU only
  std::optional<MotionPrior> motion;    // IMU (with the wheel odometry in its filter) or wheel
  std::optional<GravityPrior> gravity;  // IMU only
  bool empty() const { return !sweep && !motion && !gravity; }
};

// The adjoint of `a_from_b` (frame B's pose in frame A): a right perturbation xi_b of frame B's
// motion is the perturbation adjoint * xi_b of the motion of frame A, rigidly attached to B
// (motion_a = a_from_b * motion_b * a_from_b^-1). Carries covariances (adjoint C adjoint^T) and,
// transposed, information (adjoint^-T I adjoint^-1).
Matrix6d adjoint(const Eigen::Isometry3d& a_from_b);

}  // namespace adaptive_lego_loam
