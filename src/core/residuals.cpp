#include "adaptive_lego_loam/core/residuals.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {

ceres::Solver::Options registration_solver_options(int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

Eigen::Isometry3d euler_vector_to_pose(const double* pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = (Eigen::AngleAxisd(pose[2], Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pose[1], Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(pose[0], Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose[3], pose[4], pose[5]);
  return out;
}

void pose_to_euler_vector(const Eigen::Isometry3d& pose, double* out) {
  const Eigen::Matrix3d& r = pose.linear();
  // R = Rz(yaw) Ry(pitch) Rx(roll): r(2,0) = -sin(pitch).
  out[1] = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  out[0] = std::atan2(r(2, 1), r(2, 2));
  out[2] = std::atan2(r(1, 0), r(0, 0));
  out[3] = pose.translation().x();
  out[4] = pose.translation().y();
  out[5] = pose.translation().z();
}

}  // namespace adaptive_lego_loam
