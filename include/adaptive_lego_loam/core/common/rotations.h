#pragma once
// Rotation algebra: the cross-product matrix, the exponential and logarithm maps between rotation
// vectors and rotations, poses from a config's angles.

#include <Eigen/Geometry>

namespace adaptive_lego_loam {

// [v]x: skew(v) * w = v x w.
Eigen::Matrix3d skew(const Eigen::Vector3d& v);
// The rotation by |v| about v / |v|.
Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& v);
// The rotation vector of `rotation`, its angle in [0, pi].
Eigen::Vector3d rotation_log(const Eigen::Matrix3d& rotation);

// A pose from a config's roll, pitch, yaw (deg; R = Rz(yaw) Ry(pitch) Rx(roll)) and x, y, z (m),
// three each.
Eigen::Isometry3d pose_from_rpy_xyz(const double* rpy_deg, const double* xyz_m);

// A motion of frame B expressed as the motion of frame A rigidly attached to it, where
// `a_from_b` is B's pose in A: a_from_b * motion_b * a_from_b^-1.
Eigen::Isometry3d motion_in_frame(const Eigen::Isometry3d& motion_b,
                                  const Eigen::Isometry3d& a_from_b);

}  // namespace adaptive_lego_loam
