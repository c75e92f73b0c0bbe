#include "adaptive_lego_loam/core/odometry/residuals.h"

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/core/common/workers.h"

namespace adaptive_lego_loam {
namespace {

// Correspondences a chunk when the solver's evaluation is shared among threads.
constexpr std::size_t kMatchesPerChunk = 256;

template <int Rows, int Columns>
using RowMajor = Eigen::Matrix<double, Rows, Columns, Eigen::RowMajor>;

// m = R p + t over the Euler 6-vector, with dm/d(pose).
class EulerPose {
 public:
  static constexpr int kParameters = 6;

  explicit EulerPose(const double* pose) : translation_(pose[3], pose[4], pose[5]) {
    const double cr = std::cos(pose[0]), sr = std::sin(pose[0]);
    const double cp = std::cos(pose[1]), sp = std::sin(pose[1]);
    const double cy = std::cos(pose[2]), sy = std::sin(pose[2]);
    Eigen::Matrix3d rx, ry, rz, drx, dry, drz;
    rx << 1, 0, 0, 0, cr, -sr, 0, sr, cr;
    drx << 0, 0, 0, 0, -sr, -cr, 0, cr, -sr;
    ry << cp, 0, sp, 0, 1, 0, -sp, 0, cp;
    dry << -sp, 0, cp, 0, 0, 0, -cp, 0, -sp;
    rz << cy, -sy, 0, sy, cy, 0, 0, 0, 1;
    drz << -sy, -cy, 0, cy, -sy, 0, 0, 0, 0;
    rotation_ = rz * ry * rx;
    d_roll_ = rz * ry * drx;
    d_pitch_ = rz * dry * rx;
    d_yaw_ = drz * ry * rx;
  }

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return rotation_ * p + translation_; }

  RowMajor<3, 6> jacobian(const Eigen::Vector3d& p) const {
    RowMajor<3, 6> j;
    j.col(0) = d_roll_ * p;
    j.col(1) = d_pitch_ * p;
    j.col(2) = d_yaw_ * p;
    j.rightCols<3>().setIdentity();
    return j;
  }

 private:
  Eigen::Matrix3d rotation_, d_roll_, d_pitch_, d_yaw_;
  Eigen::Vector3d translation_;
};

// m = q p q* + t, as Eigen rotates (p + 2w (v x p) + 2 v x (v x p), q = (v, w)), with
// dm/d(x, y, z, w, tx, ty, tz).
class QuaternionPose {
 public:
  static constexpr int kParameters = 7;

  QuaternionPose(const double* rotation, const double* translation)
      : v_(rotation[0], rotation[1], rotation[2]),
        w_(rotation[3]),
        translation_(translation[0], translation[1], translation[2]) {
    const Eigen::Matrix3d v_cross = skew(v_);
    rotation_ = Eigen::Matrix3d::Identity() + 2.0 * w_ * v_cross + 2.0 * v_cross * v_cross;
  }

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return rotation_ * p + translation_; }

  RowMajor<3, 7> jacobian(const Eigen::Vector3d& p) const {
    RowMajor<3, 7> j;
    j.leftCols<3>() = 2.0 * (v_.dot(p) * Eigen::Matrix3d::Identity() + v_ * p.transpose() -
                             2.0 * p * v_.transpose() - w_ * skew(p));
    j.col(3) = 2.0 * v_.cross(p);
    j.rightCols<3>().setIdentity();
    return j;
  }

 private:
  Eigen::Vector3d v_;
  double w_;
  Eigen::Vector3d translation_;
  Eigen::Matrix3d rotation_;
};

// m = pose * exp(xi) p at xi = 0, with dm/d(xi), xi = [rotation vector, translation] in the
// point's frame.
class BodyPerturbation {
 public:
  static constexpr int kParameters = 6;

  explicit BodyPerturbation(const Eigen::Isometry3d& pose) : pose_(pose) {}

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return pose_ * p; }

  RowMajor<3, 6> jacobian(const Eigen::Vector3d& p) const {
    RowMajor<3, 6> j;
    j.leftCols<3>() = -pose_.linear() * skew(p);
    j.rightCols<3>() = pose_.linear();
    return j;
  }

 private:
  Eigen::Isometry3d pose_;
};

// Folds a correspondence's Huber loss into its residual r and Jacobian j: beyond delta, r is
// scaled by g = sqrt(rho(s) / s), s = |r|^2, rho(s) = 2 delta sqrt(s) - delta^2, so that |r|^2
// becomes rho(s), Ceres' Huber cost; j becomes the exact derivative of the scaled residual. (Ceres'
// per-block loss has the same cost; its Gauss-Newton model weighs the outliers' curvature up to
// twice as much.)
template <int Rows, int Columns>
void apply_huber(double delta, Eigen::Matrix<double, Rows, 1>& r, RowMajor<Rows, Columns>* j) {
  const double s = r.squaredNorm();
  if (s <= delta * delta) return;
  const double norm = std::sqrt(s);
  const double g = std::sqrt((2.0 * delta * norm - delta * delta) / s);
  if (j) {
    // dg/ds = (rho'(s) s - rho(s)) / (2 g s^2), rho'(s) = delta / sqrt(s).
    const double dg_ds = delta * (delta - norm) / (2.0 * g * s * s);
    *j = g * *j + (2.0 * dg_ds) * r * (r.transpose() * *j);
  }
  r *= g;
}

// Residuals of the chosen correspondences at `pose`, 3 per line ((m - through) x direction, the
// distance vector) and 1 per plane; with `with_jacobian`, each residual's Jacobian row goes to
// write_row(row, values). With `shared`, the correspondences are split among the current workers:
// write_row must then only write its own row.
template <class Pose, class WriteRow>
void evaluate_matches(const Pose& pose, const Correspondences& matches, MatchKinds kinds,
                      double huber_loss, bool with_jacobian, double* residuals,
                      const WriteRow& write_row, bool shared = false) {
  constexpr int kParameters = Pose::kParameters;
  const std::size_t lines = kinds == MatchKinds::kPlanes ? 0 : matches.lines.size();
  const std::size_t planes = kinds == MatchKinds::kLines ? 0 : matches.planes.size();
  const auto evaluate_line = [&](std::size_t index) {
    const LineMatch& line = matches.lines[index];
    Eigen::Vector3d r = (pose.apply(line.point) - line.through).cross(line.direction);
    RowMajor<3, kParameters> j;
    if (with_jacobian) j = -skew(line.direction) * pose.jacobian(line.point);
    apply_huber<3, kParameters>(huber_loss, r, with_jacobian ? &j : nullptr);
    r *= line.scale;
    if (with_jacobian) j *= line.scale;
    for (int k = 0; k < 3; ++k) {
      const int row = static_cast<int>(3 * index) + k;
      residuals[row] = r[k];
      if (with_jacobian) write_row(row, j.row(k).data());
    }
  };
  const auto evaluate_plane = [&](std::size_t index) {
    const PlaneMatch& plane = matches.planes[index];
    Eigen::Matrix<double, 1, 1> r(plane.normal.dot(pose.apply(plane.point)) + plane.offset);
    RowMajor<1, kParameters> j;
    if (with_jacobian) j = plane.normal.transpose() * pose.jacobian(plane.point);
    apply_huber<1, kParameters>(huber_loss, r, with_jacobian ? &j : nullptr);
    r *= plane.scale;
    if (with_jacobian) j *= plane.scale;
    const int row = static_cast<int>(3 * lines + index);
    residuals[row] = r[0];
    if (with_jacobian) write_row(row, j.data());
  };
  const auto evaluate = [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      if (k < lines) {
        evaluate_line(k);
      } else {
        evaluate_plane(k - lines);
      }
    }
  };
  if (shared) {
    for_chunks(lines + planes, kMatchesPerChunk, evaluate);
  } else {
    evaluate(0, 0, lines + planes);
  }
}

int residual_count(const Correspondences& matches, MatchKinds kinds) {
  const int lines = kinds == MatchKinds::kPlanes ? 0 : 3 * static_cast<int>(matches.lines.size());
  const int planes = kinds == MatchKinds::kLines ? 0 : static_cast<int>(matches.planes.size());
  return lines + planes;
}

}  // namespace

EulerRegistrationCost::EulerRegistrationCost(const Correspondences& matches, MatchKinds kinds,
                                             double huber_loss)
    : matches_(matches), kinds_(kinds), huber_loss_(huber_loss) {
  set_num_residuals(residual_count(matches, kinds));
  mutable_parameter_block_sizes()->push_back(6);
}

bool EulerRegistrationCost::Evaluate(double const* const* parameters, double* residuals,
                                     double** jacobians) const {
  double* jacobian = jacobians ? jacobians[0] : nullptr;
  const auto write_row = [jacobian](int row, const double* values) {
    std::copy(values, values + 6, jacobian + 6 * row);
  };
  evaluate_matches(EulerPose(parameters[0]), matches_, kinds_, huber_loss_, jacobian != nullptr,
                   residuals, write_row, true);
  return true;
}

QuaternionRegistrationCost::QuaternionRegistrationCost(const Correspondences& matches,
                                                       double huber_loss)
    : matches_(matches), huber_loss_(huber_loss) {
  set_num_residuals(residual_count(matches, MatchKinds::kBoth));
  mutable_parameter_block_sizes()->push_back(4);
  mutable_parameter_block_sizes()->push_back(3);
}

bool QuaternionRegistrationCost::Evaluate(double const* const* parameters, double* residuals,
                                          double** jacobians) const {
  double* rotation = jacobians ? jacobians[0] : nullptr;
  double* translation = jacobians ? jacobians[1] : nullptr;
  const auto write_row = [rotation, translation](int row, const double* values) {
    if (rotation) std::copy(values, values + 4, rotation + 4 * row);
    if (translation) std::copy(values + 4, values + 7, translation + 3 * row);
  };
  evaluate_matches(QuaternionPose(parameters[0], parameters[1]), matches_, MatchKinds::kBoth,
                   huber_loss_, rotation || translation, residuals, write_row, true);
  return true;
}

Eigen::Matrix<double, 6, 6> correspondence_information(const Correspondences& matches,
                                                       const Eigen::Isometry3d& pose,
                                                       double huber_loss, double sigma) {
  std::vector<double> residuals(residual_count(matches, MatchKinds::kBoth));
  Eigen::Matrix<double, 6, 6> sum = Eigen::Matrix<double, 6, 6>::Zero();
  const auto add_row = [&sum](int, const double* values) {
    const Eigen::Map<const Eigen::Matrix<double, 6, 1>> row(values);
    sum.selfadjointView<Eigen::Lower>().rankUpdate(row);
  };
  evaluate_matches(BodyPerturbation(pose), matches, MatchKinds::kBoth, huber_loss, true,
                   residuals.data(), add_row);
  const Eigen::Matrix<double, 6, 6> full = sum.selfadjointView<Eigen::Lower>();
  return full / (sigma * sigma);
}

ceres::Solver::Options registration_solver_options(int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
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
