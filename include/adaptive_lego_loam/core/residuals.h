#pragma once
// Ceres residuals of LOAM-style registration: point-to-line and point-to-plane distances of a
// transformed point, for the two pose parameterisations the core uses.
//   Euler: 6 doubles [roll, pitch, yaw, x, y, z], R = Rz(yaw) Ry(pitch) Rx(roll) (scan-to-scan,
//          so that LeGO-LOAM's two-step solve can hold roll/pitch/z or yaw/x/y fixed).
//   Quaternion: 4 doubles (Eigen order x, y, z, w; EigenQuaternionManifold) + 3 translation.

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace adaptive_lego_loam {

template <typename T>
Eigen::Matrix<T, 3, 1> apply_euler_pose(const T* pose, const Eigen::Vector3d& point) {
  const T cr = cos(pose[0]), sr = sin(pose[0]);
  const T cp = cos(pose[1]), sp = sin(pose[1]);
  const T cy = cos(pose[2]), sy = sin(pose[2]);
  const T x = T(point.x()), y = T(point.y()), z = T(point.z());
  // Rx(roll), then Ry(pitch), then Rz(yaw).
  const T y1 = cr * y - sr * z, z1 = sr * y + cr * z;
  const T x2 = cp * x + sp * z1, z2 = -sp * x + cp * z1;
  return {cy * x2 - sy * y1 + pose[3], sy * x2 + cy * y1 + pose[4], z2 + pose[5]};
}

template <typename T>
Eigen::Matrix<T, 3, 1> apply_quaternion_pose(const T* rotation, const T* translation,
                                             const Eigen::Vector3d& point) {
  const Eigen::Map<const Eigen::Quaternion<T>> q(rotation);
  return q * point.cast<T>() + Eigen::Map<const Eigen::Matrix<T, 3, 1>>(translation);
}

// Distance vector from `moved` to the line through a and b.
template <typename T>
void line_residual(const Eigen::Matrix<T, 3, 1>& moved, const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b, T* residual) {
  const Eigen::Matrix<T, 3, 1> cross = (moved - a.cast<T>()).cross(moved - b.cast<T>());
  const T length = T((a - b).norm());
  for (int i = 0; i < 3; ++i)
    residual[i] = cross[i] / length;
}

struct EulerPointToLine {
  Eigen::Vector3d point, a, b;
  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    line_residual(apply_euler_pose(pose, point), a, b, residual);
    return true;
  }
  static ceres::CostFunction* create(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b) {
    return new ceres::AutoDiffCostFunction<EulerPointToLine, 3, 6>(new EulerPointToLine{p, a, b});
  }
};

struct EulerPointToPlane {
  Eigen::Vector3d point, normal;
  double offset;  // plane: normal . x + offset = 0, |normal| = 1
  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    residual[0] = normal.cast<T>().dot(apply_euler_pose(pose, point)) + T(offset);
    return true;
  }
  static ceres::CostFunction* create(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double d) {
    return new ceres::AutoDiffCostFunction<EulerPointToPlane, 1, 6>(new EulerPointToPlane{p, n, d});
  }
};

struct QuaternionPointToLine {
  Eigen::Vector3d point, a, b;
  template <typename T>
  bool operator()(const T* rotation, const T* translation, T* residual) const {
    line_residual(apply_quaternion_pose(rotation, translation, point), a, b, residual);
    return true;
  }
  static ceres::CostFunction* create(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b) {
    return new ceres::AutoDiffCostFunction<QuaternionPointToLine, 3, 4, 3>(
        new QuaternionPointToLine{p, a, b});
  }
};

struct QuaternionPointToPlane {
  Eigen::Vector3d point, normal;
  double offset;
  template <typename T>
  bool operator()(const T* rotation, const T* translation, T* residual) const {
    residual[0] =
        normal.cast<T>().dot(apply_quaternion_pose(rotation, translation, point)) + T(offset);
    return true;
  }
  static ceres::CostFunction* create(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double d) {
    return new ceres::AutoDiffCostFunction<QuaternionPointToPlane, 1, 4, 3>(
        new QuaternionPointToPlane{p, n, d});
  }
};

// Options of the core's small registration problems (6 parameters, thousands of residuals):
// dense QR, one thread (deterministic), silent.
ceres::Solver::Options registration_solver_options(int max_iterations);

// 6-vector [roll, pitch, yaw, x, y, z] <-> pose.
Eigen::Isometry3d euler_vector_to_pose(const double* pose);
void pose_to_euler_vector(const Eigen::Isometry3d& pose, double* out);

}  // namespace adaptive_lego_loam
