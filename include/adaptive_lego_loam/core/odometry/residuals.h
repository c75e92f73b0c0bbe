#pragma once
// Ceres cost functions of LOAM-style registration: point-to-line and point-to-plane distances of
// the scan's feature points moved by a pose, for the two pose parameterisations the core uses.
//   Euler: 6 doubles [roll, pitch, yaw, x, y, z], R = Rz(yaw) Ry(pitch) Rx(roll) (scan-to-scan,
//          so that LeGO-LOAM's two-step solve can hold roll/pitch/z or yaw/x/y fixed).
//   Quaternion: 4 doubles (Eigen order x, y, z, w; EigenQuaternionManifold) + 3 translation.
//
// All correspondences of one solve form one cost function with analytic derivatives: one
// automatically differentiated residual block per correspondence spent most of a solve in dual
// numbers and Ceres' per-block bookkeeping. Each correspondence keeps its own Huber loss (see
// huber_residual in residuals.cpp), so the cost is the same as with per-block losses.

#include <ceres/cost_function.h>
#include <ceres/solver.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace adaptive_lego_loam {

// A feature point (scan frame) and the line it should lie on (target frame): through `through`,
// along the unit vector `direction`. Each match's residual (after its Huber loss) is multiplied by
// `scale`: its cost weighs scale^2.
struct LineMatch {
  Eigen::Vector3d point, through, direction;
  double scale = 1.0;
};
// A feature point (scan frame) and the plane normal . x + offset = 0, |normal| = 1 (target frame).
struct PlaneMatch {
  Eigen::Vector3d point, normal;
  double offset;
  double scale = 1.0;
};

struct Correspondences {
  std::vector<LineMatch> lines;
  std::vector<PlaneMatch> planes;
  void clear() {
    lines.clear();
    planes.clear();
  }
  int size() const { return static_cast<int>(lines.size() + planes.size()); }
};

// Which correspondences a cost function uses (LeGO-LOAM's two-step odometry solves each kind
// alone).
enum class MatchKinds : int { kLines, kPlanes, kBoth };

// Residuals over the Euler 6-vector: 3 per line (the distance vector), 1 per plane.
class EulerRegistrationCost : public ceres::CostFunction {
 public:
  // Keeps a reference to `matches`, which must outlive it.
  EulerRegistrationCost(const Correspondences& matches, MatchKinds kinds, double huber_loss);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const Correspondences& matches_;
  MatchKinds kinds_;
  double huber_loss_;
};

// The same over a quaternion block (4) and a translation block (3).
class QuaternionRegistrationCost : public ceres::CostFunction {
 public:
  QuaternionRegistrationCost(const Correspondences& matches, double huber_loss);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const Correspondences& matches_;
  double huber_loss_;
};

// The information of the correspondences about a right perturbation of `pose` (the scan's pose in
// the target frame; pose * exp(xi), xi = [rotation vector, translation], the scan's own frame):
// the sum of J^T J over the residuals as the solve weighs them (each correspondence's Huber loss
// and scale), divided by sigma^2, sigma the residuals' 1-sigma error (m).
Eigen::Matrix<double, 6, 6> correspondence_information(const Correspondences& matches,
                                                       const Eigen::Isometry3d& pose,
                                                       double huber_loss, double sigma);

// Options of the core's small registration problems (6 or 7 parameters, one cost function):
// dense normal equations, one thread (deterministic), silent.
ceres::Solver::Options registration_solver_options(int max_iterations);

// 6-vector [roll, pitch, yaw, x, y, z] <-> pose.
Eigen::Isometry3d euler_vector_to_pose(const double* pose);
void pose_to_euler_vector(const Eigen::Isometry3d& pose, double* out);

}  // namespace adaptive_lego_loam
