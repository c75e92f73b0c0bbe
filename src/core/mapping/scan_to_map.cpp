#include "adaptive_lego_loam/core/mapping/scan_to_map.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/problem.h>
#include <ceres/rotation.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/core/common/workers.h"
#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/core/odometry/residuals.h"

namespace adaptive_lego_loam {
namespace {

constexpr int kNeighbours = 5;
constexpr float kMaxNeighbourDistance = 1.0f;  // m, as LOAM
constexpr double kMaxPlaneDeviation = 0.2;     // m
constexpr int kMinMatches = 20;
constexpr float kSearchRadius = LocalMap::kSearchRadius;

// Pulls the translation along `direction` toward `target`.
struct DirectionPrior {
  Eigen::Vector3d direction, target;
  double weight;
  template <typename T>
  bool operator()(const T* translation, T* residual) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t(translation);
    residual[0] = T(weight) * direction.cast<T>().dot(t - target.cast<T>());
    return true;
  }
};

// Walls' normals (sensor frame) turned into the map frame have no component along `up`. The sum
// over patches, sum_i w_i^2 (up . R n_i)^2 = |root R^T up|^2 with root^2 = sum_i w_i^2 n_i n_i^T,
// is one residual block of three, however many patches.
struct VerticalWalls {
  Eigen::Matrix3d root;
  Eigen::Vector3d up;
  template <typename T>
  bool operator()(const T* rotation, T* residual) const {
    const Eigen::Quaternion<T> q(rotation[3], rotation[0], rotation[1], rotation[2]);
    const Eigen::Matrix<T, 3, 1> up_in_sensor = q.conjugate() * up.cast<T>();
    Eigen::Map<Eigen::Matrix<T, 3, 1>> out(residual);
    out = root.cast<T>() * up_in_sensor;
    return true;
  }
};
// The motion sensors' prior on the motion since the previous scan: with E = (previous * prior)^-1
// pose, the residual root [rotation vector of E, translation of E], root^T root the prior's
// information in the correspondences' units.
struct MotionPriorResidual {
  Eigen::Quaterniond rotation;  // of (previous * prior)^-1
  Eigen::Vector3d translation;
  Matrix6d root;
  template <typename T>
  bool operator()(const T* q, const T* t, T* residual) const {
    const Eigen::Quaternion<T> pose(q[3], q[0], q[1], q[2]);
    const Eigen::Quaternion<T> error = rotation.cast<T>() * pose;
    const T wxyz[4] = {error.w(), error.x(), error.y(), error.z()};
    Eigen::Matrix<T, 6, 1> xi;
    ceres::QuaternionToAngleAxis(wxyz, xi.data());
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> position(t);
    xi.template tail<3>() = rotation.cast<T>() * position + translation.cast<T>();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> out(residual);
    out = root.cast<T>() * xi;
    return true;
  }
};

// Gravity's up seen from the sensor: root (R^T up - measured up).
struct GravityResidual {
  Eigen::Vector3d up, measured;
  Eigen::Matrix3d root;
  template <typename T>
  bool operator()(const T* q, T* residual) const {
    const Eigen::Quaternion<T> rotation(q[3], q[0], q[1], q[2]);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> out(residual);
    out = root.cast<T>() * (rotation.conjugate() * up.cast<T>() - measured.cast<T>());
    return true;
  }
};

// The symmetric square root of a covariance's (pseudo-)inverse: directions it does not constrain
// get none.
template <int N>
Eigen::Matrix<double, N, N> information_root(const Eigen::Matrix<double, N, N>& information) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> solver(information);
  const Eigen::Matrix<double, N, 1> roots = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return solver.eigenvectors() * roots.asDiagonal() * solver.eigenvectors().transpose();
}

template <int N>
Eigen::Matrix<double, N, N> pseudo_inverse(const Eigen::Matrix<double, N, N>& covariance) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> solver(covariance);
  const double largest = solver.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::Matrix<double, N, 1> inverse = Eigen::Matrix<double, N, 1>::Zero();
  for (int k = 0; k < N; ++k)
    if (solver.eigenvalues()(k) > 1e-9 * largest) inverse(k) = 1.0 / solver.eigenvalues()(k);
  return solver.eigenvectors() * inverse.asDiagonal() * solver.eigenvectors().transpose();
}

// The part of a prior's information (6 x 6) on the directions the correspondences leave open:
// the translation's and the rotation's principal directions (the other marginalised) whose sigma
// is beyond the thresholds. There the prior replaces what the scene cannot measure; elsewhere the
// match is the LiDAR's alone, which the motion sensors then learn from without counting their own
// prediction twice.
Matrix6d on_degenerate_directions(const Matrix6d& prior, const Observability& seen,
                                  double translation_sigma, double rotation_sigma) {
  Matrix6d projector = Matrix6d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (seen.rotation_sigma(k) > rotation_sigma) {
      const Eigen::Vector3d v = seen.rotation_directions.col(k);
      projector.topLeftCorner<3, 3>() += v * v.transpose();
    }
    if (seen.translation_sigma(k) > translation_sigma) {
      const Eigen::Vector3d v = seen.translation_directions.col(k);
      projector.bottomRightCorner<3, 3>() += v * v.transpose();
    }
  }
  return projector * prior * projector;
}

// A prior is trusted up to about this many of its sigmas, then its pull fades (a slipping wheel,
// an IMU after a knock).
constexpr double kPriorRobustSigmas = 5.0;

// Each patch weighs by Tukey's biweight of its tilt from vertical at the guess, nothing at
// max_tilt_deg: a steep slope (an embankment, a battered retaining wall) that the guess shows
// nearly upright must not pull the map toward it, or each scan's pull tilts the next guess
// further.
std::unique_ptr<ceres::CostFunction> vertical_walls_cost(
    const std::vector<Eigen::Vector3d>& normals, const Eigen::Matrix3d& guess_rotation,
    const Eigen::Vector3d& up, double weight, double max_tilt_deg) {
  const double limit = std::sin(max_tilt_deg * M_PI / 180.0);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& normal : normals) {
    const double tilt = up.dot(guess_rotation * normal) / limit;
    if (std::fabs(tilt) >= 1.0) continue;
    const double biweight = (1.0 - tilt * tilt) * (1.0 - tilt * tilt);
    sum += biweight * normal * normal.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(weight * weight * sum);
  const Eigen::Vector3d roots = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Matrix3d root =
      solver.eigenvectors() * roots.asDiagonal() * solver.eigenvectors().transpose();
  return std::make_unique<ceres::AutoDiffCostFunction<VerticalWalls, 3, 4>>(
      new VerticalWalls{root, up});
}

// A line through the neighbours when one spread dominates.
std::optional<LineMatch> fit_line(const Eigen::Vector3f* neighbours,
                                  const Eigen::Vector3d& sensor_point) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int k = 0; k < kNeighbours; ++k)
    centroid += neighbours[k].cast<double>();
  centroid /= kNeighbours;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int k = 0; k < kNeighbours; ++k) {
    const Eigen::Vector3d d = neighbours[k].cast<double>() - centroid;
    covariance += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance / kNeighbours);
  if (solver.eigenvalues()(2) < 3.0 * solver.eigenvalues()(1)) return std::nullopt;
  return LineMatch{sensor_point, centroid, solver.eigenvectors().col(2)};
}

// A plane through the neighbours when none lies more than kMaxPlaneDeviation off it.
std::optional<PlaneMatch> fit_plane(const Eigen::Vector3f* neighbours,
                                    const Eigen::Vector3d& sensor_point) {
  // n . x = -1 in the least-squares sense, then normalised: the plane n . x + d = 0. By the
  // normal equations (3 x 3; a QR of the 5 x 3 system took a tenth of the mapping).
  Eigen::Matrix<double, kNeighbours, 3> points;
  for (int k = 0; k < kNeighbours; ++k)
    points.row(k) = neighbours[k].cast<double>();
  const Eigen::Matrix3d gram = points.transpose() * points;
  Eigen::Vector3d normal = gram.ldlt().solve(-points.colwise().sum().transpose());
  const double norm = normal.norm();
  if (!(norm > 1e-9) || !std::isfinite(norm)) return std::nullopt;
  normal /= norm;
  const double offset = 1.0 / norm;
  for (int k = 0; k < kNeighbours; ++k) {
    if (std::fabs(normal.dot(points.row(k).transpose()) + offset) > kMaxPlaneDeviation) {
      return std::nullopt;
    }
  }
  return PlaneMatch{sensor_point, normal, offset};
}

// Each scan point's correspondence of one kind (a line on the map's corners or a plane on its
// surfaces), fitted to its kNeighbours nearest map points when all lie within LOAM's 1 m. Later
// iterations search again only for points that moved more than `keep_distance` and enough to
// change that: the distance to a query's k-th nearest point changes by at most the distance the
// query moved, so with the 5th and 6th nearest distances kept, a point that moved by m keeps its
// neighbours while 5th + 2 m < 6th, its acceptance while 5th + m <= 1 m, and its rejection while
// 5th - m > 1 m.
template <class Match>
class CorrespondenceCache {
 public:
  using Fit = std::optional<Match> (*)(const Eigen::Vector3f*, const Eigen::Vector3d&);

  CorrespondenceCache(const Cloud& scan, const VoxelMap& map, Fit fit, float keep_distance)
      : scan_(scan), map_(map), fit_(fit), keep_distance_(keep_distance), entries_(scan.size()) {}

  // The correspondences with the scan placed by (rotation, translation), in scan order (the
  // points split among the current workers).
  void update(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation,
              std::vector<Match>& out) {
    out.clear();
    append_in_order(scan_.size(), kPointsPerChunk, out, [&](std::size_t i, std::vector<Match>& to) {
      const Eigen::Vector3d sensor_point = scan_[i].getVector3fMap().cast<double>();
      const Eigen::Vector3f at = (rotation * sensor_point + translation).cast<float>();
      Entry& entry = entries_[i];
      if (!entry.searched || !still_valid(entry, at)) search(at, sensor_point, entry);
      if (entry.match) to.push_back(*entry.match);
    });
  }

 private:
  static constexpr std::size_t kPointsPerChunk = 128;

  struct Entry {
    bool searched = false;
    Eigen::Vector3f searched_at;
    float fifth = 0.f;  // distance to the 5th nearest map point (kSearchRadius: none that near)
    float sixth = 0.f;  // ... to the 6th (kSearchRadius: none that near)
    std::optional<Match> match;
  };

  bool still_valid(const Entry& entry, const Eigen::Vector3f& at) const {
    const float moved = (at - entry.searched_at).norm();
    if (moved <= keep_distance_) return true;
    if (entry.fifth - moved > kMaxNeighbourDistance) return true;
    return entry.fifth + moved <= kMaxNeighbourDistance && entry.fifth + 2.f * moved < entry.sixth;
  }

  void search(const Eigen::Vector3f& at, const Eigen::Vector3d& sensor_point, Entry& entry) const {
    Eigen::Vector3f neighbours[kNeighbours + 1];
    float squared[kNeighbours + 1];
    const int found =
        map_.nearest(at, kNeighbours + 1, neighbours, squared, kSearchRadius * kSearchRadius);
    entry.searched = true;
    entry.searched_at = at;
    entry.fifth = found >= kNeighbours ? std::sqrt(squared[kNeighbours - 1]) : kSearchRadius;
    entry.sixth = found > kNeighbours ? std::sqrt(squared[kNeighbours]) : kSearchRadius;
    const bool close = found >= kNeighbours &&
                       squared[kNeighbours - 1] <= kMaxNeighbourDistance * kMaxNeighbourDistance;
    entry.match = close ? fit_(neighbours, sensor_point) : std::nullopt;
  }

  const Cloud& scan_;
  const VoxelMap& map_;
  Fit fit_;
  float keep_distance_;
  std::vector<Entry> entries_;
};

// J^T J of the problem in the tangent space of (rotation, translation).
Eigen::Matrix<double, 6, 6> normal_matrix(ceres::Problem& problem, double* rotation,
                                          double* translation) {
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = {rotation, translation};
  options.num_threads = 1;
  ceres::CRSMatrix jacobian;
  problem.Evaluate(options, nullptr, nullptr, nullptr, &jacobian);
  Eigen::Matrix<double, 6, 6> jtj = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 1, 6> row;
  for (int r = 0; r < jacobian.num_rows; ++r) {
    row.setZero();
    for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k)
      row(jacobian.cols[k]) = jacobian.values[k];
    jtj += row.transpose() * row;
  }
  return jtj;
}

}  // namespace

struct SteppedMapMatch::State {
  State(const MappingParams& params, const Cloud& corners, const Cloud& surfaces,
        const LocalMap& map, const Eigen::Isometry3d& guess,
        const std::optional<WeakDirectionPrior>& prior, const SensorPriors& sensors)
      : params(params),
        map(map),
        prior(prior),
        sensors(sensors),
        guess(guess),
        placed_guess(map.to_placement() * guess),
        rotation(placed_guess.linear()),
        translation(placed_guess.translation()),
        lines(corners, map.corner_map(), fit_line,
              static_cast<float>(params.keep_correspondence_distance)),
        planes(surfaces, map.surface_map(), fit_plane,
               static_cast<float>(params.keep_correspondence_distance)) {}

  // Returns whether the match goes on.
  bool iterate();
  // LOAM's degeneracy test on the first iteration's problem: directions whose eigenvalue of J^T J
  // is small get no update, unless the motion sensors' priors hold them.
  void find_degenerate_directions(ceres::Problem& problem, double* q, double* t);
  // The motion sensors' residual blocks (made once), added to an iteration's problem, and their
  // J^T J in the solver's tangent space.
  // The gravity prior's cost (made with the match), the motion prior's (made on the first
  // iteration's correspondences: it holds where they do not), both added to each iteration.
  void make_gravity_cost();
  void make_motion_cost();
  void add_sensor_priors(ceres::Problem& problem, double* q, double* t);
  Eigen::Matrix<double, 6, 6> sensor_prior_normal_matrix() const;
  // The priors' normal matrix about a right perturbation of the pose (sensor frame), in the
  // residuals' units (residual_sigma^2 times their information).
  Matrix6d sensor_prior_body_normal() const;

  MappingParams params;
  const LocalMap& map;
  std::optional<WeakDirectionPrior> prior;
  SensorPriors sensors;
  Eigen::Isometry3d guess, placed_guess;  // the latter in the frame the map's points are in
  Eigen::Quaterniond rotation;
  Eigen::Vector3d translation;
  Eigen::Matrix<double, 6, 6> keep = Eigen::Matrix<double, 6, 6>::Identity();
  Correspondences matches;
  ceres::EigenQuaternionManifold quaternion_manifold;
  CorrespondenceCache<LineMatch> lines;
  CorrespondenceCache<PlaneMatch> planes;
  std::unique_ptr<ceres::CostFunction> walls_cost;
  std::unique_ptr<ceres::CostFunction> motion_cost, gravity_cost;
  std::unique_ptr<ceres::LossFunction> motion_loss;
  Matrix6d motion_information = Matrix6d::Zero();  // the part of the prior that is used
  Eigen::Matrix3d gravity_root = Eigen::Matrix3d::Zero();
  MapMatchResult result;
  int iteration = 0;
  int held_directions = 0;  // of the 6, held at the guess (degenerate and not held by a prior)
  bool done = false;
};

void SteppedMapMatch::State::make_motion_cost() {
  if (!sensors.motion) return;
  const double sigma = params.residual_sigma;
  Eigen::Isometry3d placed = Eigen::Isometry3d::Identity();
  placed.linear() = rotation.toRotationMatrix();
  placed.translation() = translation;
  Matrix6d lidar = correspondence_information(matches, placed, params.huber_loss, sigma);
  if (sensors.scene) {
    lidar = discounted_along(lidar, sensors.scene->weak_direction, 1.0 - sensors.scene->mu);
  }
  result.lidar_observability = observability(lidar);
  motion_information = on_degenerate_directions(
      sensors.motion->information, *result.lidar_observability, params.degenerate_translation_sigma,
      params.degenerate_rotation_sigma_deg * M_PI / 180.0);
  if (motion_information.isZero()) return;
  const Eigen::Isometry3d inverse =
      (map.to_placement() * sensors.previous * sensors.motion->motion).inverse();
  const Matrix6d root = sigma * information_root<6>(motion_information);
  motion_cost.reset(new ceres::AutoDiffCostFunction<MotionPriorResidual, 6, 4, 3>(
      new MotionPriorResidual{Eigen::Quaterniond(inverse.linear()), inverse.translation(), root}));
  motion_loss.reset(new ceres::CauchyLoss(kPriorRobustSigmas * sigma));
}

void SteppedMapMatch::State::make_gravity_cost() {
  const double sigma = params.residual_sigma;
  const Eigen::Isometry3d placement = map.to_placement();
  if (sensors.gravity) {
    const Eigen::Matrix3d covariance =
        sensors.gravity->covariance +
        std::pow(params.gravity_sigma_deg * M_PI / 180.0, 2) * Eigen::Matrix3d::Identity();
    // Only across the measured up: along it a unit vector cannot err.
    const Eigen::Vector3d& up = sensors.gravity->up;
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - up * up.transpose();
    gravity_root = sigma * information_root<3>(
                               across * pseudo_inverse<3>(across * covariance * across) * across);
    gravity_cost.reset(new ceres::AutoDiffCostFunction<GravityResidual, 3, 4>(
        new GravityResidual{placement.linear() * sensors.map_up, up, gravity_root}));
  }
}

void SteppedMapMatch::State::add_sensor_priors(ceres::Problem& problem, double* q, double* t) {
  if (motion_cost) {
    problem.AddResidualBlock(motion_cost.get(), motion_loss.get(), q, t);
    result.motion_prior = true;
    result.prior_from_imu = sensors.motion->from_imu;
    result.prior_from_wheel = sensors.motion->from_wheel;
  }
  if (gravity_cost) problem.AddResidualBlock(gravity_cost.get(), nullptr, q);
}

Matrix6d SteppedMapMatch::State::sensor_prior_body_normal() const {
  const double sigma = params.residual_sigma;
  Matrix6d body = Matrix6d::Zero();
  if (motion_cost) body += sigma * sigma * motion_information;
  if (gravity_cost) {
    const Eigen::Matrix3d r = rotation.toRotationMatrix();
    const Eigen::Vector3d seen = r.transpose() * (map.to_placement().linear() * sensors.map_up);
    const Eigen::Matrix3d j = gravity_root * skew(seen);
    body.topLeftCorner<3, 3>() += j.transpose() * j;
  }
  return body;
}

Eigen::Matrix<double, 6, 6> SteppedMapMatch::State::sensor_prior_normal_matrix() const {
  // At the pose of the first iteration: body perturbations [phi, rho] from the solver's tangent
  // [delta, dt] (Ceres' quaternion: R' = exp(2 delta) R, t' = t + dt): phi = 2 R^T delta,
  // rho = R^T dt.
  const Eigen::Matrix3d r = rotation.toRotationMatrix();
  Matrix6d to_body = Matrix6d::Zero();
  to_body.topLeftCorner<3, 3>() = 2.0 * r.transpose();
  to_body.bottomRightCorner<3, 3>() = r.transpose();
  return to_body.transpose() * sensor_prior_body_normal() * to_body;
}

void SteppedMapMatch::State::find_degenerate_directions(ceres::Problem& problem, double* q,
                                                        double* t) {
  const Eigen::Matrix<double, 6, 6> lidar = normal_matrix(problem, q, t);
  const auto held = [&](const Eigen::Matrix<double, 6, 6>& normal, int& count) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(normal);
    Eigen::Matrix<double, 6, 6> projector = Eigen::Matrix<double, 6, 6>::Zero();
    count = 0;
    for (int k = 0; k < 6; ++k) {
      const Eigen::Matrix<double, 6, 1> v = solver.eigenvectors().col(k);
      if (solver.eigenvalues()(k) < params.degeneracy_eigenvalue) {
        ++count;
      } else {
        projector += v * v.transpose();
      }
    }
    return std::make_pair(projector, solver.eigenvalues()(0));
  };
  const auto [projector, smallest] = held(lidar, result.degenerate_directions);
  result.smallest_eigenvalue = smallest;
  keep = projector;
  held_directions = result.degenerate_directions;
  if (!sensors.empty() && held_directions > 0) {
    keep = held(lidar + sensor_prior_normal_matrix(), held_directions).first;
  }
}

bool SteppedMapMatch::State::iterate() {
  const Eigen::Matrix3d rotation_matrix = rotation.toRotationMatrix();
  lines.update(rotation_matrix, translation, matches.lines);
  planes.update(rotation_matrix, translation, matches.planes);
  result.edge_matches = static_cast<int>(matches.lines.size());
  result.plane_matches = static_cast<int>(matches.planes.size());
  if (result.edge_matches + result.plane_matches < kMinMatches) return false;

  double q[4] = {rotation.x(), rotation.y(), rotation.z(), rotation.w()};
  double t[3] = {translation.x(), translation.y(), translation.z()};
  QuaternionRegistrationCost cost(matches, params.huber_loss);
  std::unique_ptr<ceres::CostFunction> prior_cost;
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddParameterBlock(q, 4, &quaternion_manifold);
  problem.AddParameterBlock(t, 3);
  problem.AddResidualBlock(&cost, nullptr, q, t);
  if (walls_cost) problem.AddResidualBlock(walls_cost.get(), nullptr, q);
  if (prior && prior->weight > 0.0) {
    prior_cost.reset(new ceres::AutoDiffCostFunction<DirectionPrior, 1, 3>(new DirectionPrior{
        placed_guess.linear() * prior->direction, placed_guess.translation(), prior->weight}));
    problem.AddResidualBlock(prior_cost.get(), nullptr, t);
  }
  if (iteration == 0) {
    make_motion_cost();
    find_degenerate_directions(problem, q, t);
  }
  if (!sensors.empty()) add_sensor_priors(problem, q, t);
  const double q_before[4] = {q[0], q[1], q[2], q[3]};
  const double t_before[3] = {t[0], t[1], t[2]};
  ceres::Solver::Summary summary;
  ceres::Solve(registration_solver_options(params.solver_iterations), &problem, &summary);

  // The step, in the tangent space, with its degenerate part removed.
  Eigen::Matrix<double, 6, 1> step;
  quaternion_manifold.Minus(q, q_before, step.data());
  step.tail<3>() = Eigen::Vector3d(t[0] - t_before[0], t[1] - t_before[1], t[2] - t_before[2]);
  if (held_directions > 0) step = keep * step;
  double q_after[4];
  quaternion_manifold.Plus(q_before, step.data(), q_after);
  rotation = Eigen::Quaterniond(q_after[3], q_after[0], q_after[1], q_after[2]).normalized();
  translation = Eigen::Vector3d(t_before[0], t_before[1], t_before[2]) + step.tail<3>();
  result.iterations = iteration + 1;
  result.matched = true;
  const bool converged =
      iteration >= 1 && step.head<3>().norm() < 5e-5 && step.tail<3>().norm() < 1e-3;
  ++iteration;
  return !converged && iteration < params.max_iterations;
}

SteppedMapMatch::SteppedMapMatch(const MappingParams& params, const Cloud& corners,
                                 const Cloud& surfaces, const LocalMap& map,
                                 const Eigen::Isometry3d& guess,
                                 const std::optional<WeakDirectionPrior>& prior,
                                 const std::vector<Eigen::Vector3d>& wall_normals,
                                 const SensorPriors& sensors)
    : state_(std::make_unique<State>(params, corners, surfaces, map, guess, prior, sensors)) {
  State& state = *state_;
  state.done = map.empty() || params.max_iterations <= 0;
  // The vertical-structure prior, in the frame the map's points are in (the map frame's up moves
  // with it while placing again), and gravity where an IMU gives it: both, since an IMU's gravity
  // is only as level as its accelerometer's bias is known, and a bias mis-learned tilts the map.
  if (!state.done && !sensors.empty()) {
    state.make_gravity_cost();
  }
  if (!state.done && params.vertical_prior_weight > 0.0 && !wall_normals.empty()) {
    state.walls_cost =
        vertical_walls_cost(wall_normals, state.placed_guess.linear(),
                            map.to_placement().linear() * Eigen::Vector3d::UnitZ(),
                            params.vertical_prior_weight, params.vertical_prior_max_tilt_deg);
  }
}

SteppedMapMatch::~SteppedMapMatch() = default;

bool SteppedMapMatch::done() const {
  return state_->done;
}

void SteppedMapMatch::iterate() {
  if (!state_->done) state_->done = !state_->iterate();
}

MapMatchResult SteppedMapMatch::result() const {
  const State& state = *state_;
  MapMatchResult result = state.result;
  result.pose = state.guess;
  if (result.matched) {
    Eigen::Isometry3d placed_pose = Eigen::Isometry3d::Identity();
    placed_pose.linear() = state.rotation.toRotationMatrix();
    placed_pose.translation() = state.translation;
    result.pose = state.map.to_placement().inverse() * placed_pose;
    result.information = correspondence_information(
        state.matches, placed_pose, state.params.huber_loss, state.params.residual_sigma);
    result.prior_information =
        state.sensor_prior_body_normal() / std::pow(state.params.residual_sigma, 2);
  }
  return result;
}

ScanToMapMatcher::ScanToMapMatcher(const MappingParams& params) : params_(params) {}

MapMatchResult ScanToMapMatcher::match(const Cloud& corners, const Cloud& surfaces,
                                       const LocalMap& map, const Eigen::Isometry3d& guess,
                                       const std::optional<WeakDirectionPrior>& prior,
                                       const std::vector<Eigen::Vector3d>& wall_normals,
                                       const SensorPriors& sensors) const {
  SteppedMapMatch match(params_, corners, surfaces, map, guess, prior, wall_normals, sensors);
  while (!match.done())
    match.iterate();
  return match.result();
}

}  // namespace adaptive_lego_loam
