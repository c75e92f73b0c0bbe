#include "adaptive_lego_loam/core/odometry/scan_to_scan.h"

#include <ceres/manifold.h>
#include <ceres/problem.h>

#include <algorithm>
#include <cmath>

#include "adaptive_lego_loam/core/common/workers.h"
#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/core/odometry/residuals.h"

namespace adaptive_lego_loam {

namespace {

constexpr int kCandidates = 15;
// Feature points a chunk when the search is shared among threads.
constexpr std::size_t kPointsPerChunk = 64;

Eigen::Vector3d position(const CloudPoint& p) {
  return p.getVector3fMap().cast<double>();
}

int row_of(const CloudPoint& p) {
  return static_cast<int>(std::lround(p.intensity));
}

// The feature point moved into the previous scan's frame by the current estimate.
Eigen::Vector3f moved_point(const CloudPoint& p, const Eigen::Isometry3d& pose) {
  return (pose * position(p)).cast<float>();
}

// A row's spacing: the mean of its gaps to the rows beside it (the one gap at either end).
std::vector<double> ring_spacing_rad(const std::vector<double>& beam_angles_deg) {
  std::vector<double> spacing;
  const std::size_t rows = beam_angles_deg.size();
  if (rows < 2) return spacing;
  for (std::size_t row = 0; row < rows; ++row) {
    const std::size_t below = row == 0 ? 0 : row - 1, above = std::min(row + 1, rows - 1);
    const double gap_deg = (beam_angles_deg[above] - beam_angles_deg[below]) / (above - below);
    spacing.push_back(gap_deg * M_PI / 180.0);
  }
  return spacing;
}

}  // namespace

ScanToScanOdometry::ScanToScanOdometry(const OdometryParams& params,
                                       const std::vector<double>& beam_angles_deg,
                                       double scan_period)
    : params_(params), scan_period_(scan_period) {
  if (!(params.range_weight_fit_error > 0.0)) return;
  constexpr double kReferenceRange = 10.0;  // m
  for (double spacing : ring_spacing_rad(beam_angles_deg)) {
    const double blur = params.range_weight_fit_error * spacing;
    range_weighting_.push_back({blur, 0.0});
    range_weighting_.back().reference = root_weight(range_weighting_.back(), kReferenceRange);
  }
}

// sqrt(range^2 / (noise^2 + (blur x range)^2)): the root of a correspondence's weight.
double ScanToScanOdometry::root_weight(const RangeWeighting& row, double range) const {
  const double noise = params_.range_weight_noise;
  return range / std::sqrt(noise * noise + row.blur_rad * row.blur_rad * range * range);
}

// The root weight relative to a point 10 m away on the same row.
double ScanToScanOdometry::range_scale(const CloudPoint& p) const {
  if (range_weighting_.empty()) return 1.0;
  const int last_row = static_cast<int>(range_weighting_.size()) - 1;
  const RangeWeighting& row = range_weighting_[std::clamp(row_of(p), 0, last_row)];
  return root_weight(row, std::max(position(p).norm(), 1.0)) / row.reference;
}

void ScanToScanOdometry::reset() {
  previous_corners_.reset();
  first_pair_ = true;
  previous_surfaces_.reset();
}

void ScanToScanOdometry::find_edge_matches(const Cloud& sharp, const Eigen::Isometry3d& pose,
                                           Correspondences& matches) const {
  matches.lines.clear();
  if (previous_corners_->size() < 2) return;
  const float max_squared =
      static_cast<float>(params_.max_match_distance * params_.max_match_distance);
  append_in_order(sharp.size(), kPointsPerChunk, matches.lines,
                  [&](std::size_t i, std::vector<LineMatch>& out) {
                    find_edge_match(sharp[i], pose, max_squared, out);
                  });
}

void ScanToScanOdometry::find_edge_match(const CloudPoint& p, const Eigen::Isometry3d& pose,
                                         float max_squared, std::vector<LineMatch>& out) const {
  uint32_t indices[kCandidates];
  float squared[kCandidates];
  const int found =
      corner_tree_.nearest(moved_point(p, pose), kCandidates, indices, squared, max_squared);
  if (found < 2) return;
  // The line runs through the nearest edge point and the nearest one on a neighbouring row.
  const CloudPoint& nearest = (*previous_corners_)[indices[0]];
  for (int k = 1; k < found; ++k) {
    const CloudPoint& other = (*previous_corners_)[indices[k]];
    const int row_gap = std::abs(row_of(other) - row_of(nearest));
    if (row_gap == 0 || row_gap > 2) continue;
    const Eigen::Vector3d along = position(nearest) - position(other);
    if (along.norm() < 1e-6) continue;
    out.push_back({position(p), position(nearest), along.normalized(), range_scale(p)});
    return;
  }
}

void ScanToScanOdometry::find_plane_matches(const Cloud& flat, const Eigen::Isometry3d& pose,
                                            Correspondences& matches) const {
  matches.planes.clear();
  if (previous_surfaces_->size() < 3) return;
  const float max_squared =
      static_cast<float>(params_.max_match_distance * params_.max_match_distance);
  append_in_order(flat.size(), kPointsPerChunk, matches.planes,
                  [&](std::size_t i, std::vector<PlaneMatch>& out) {
                    find_plane_match(flat[i], pose, max_squared, out);
                  });
}

void ScanToScanOdometry::find_plane_match(const CloudPoint& p, const Eigen::Isometry3d& pose,
                                          float max_squared, std::vector<PlaneMatch>& out) const {
  uint32_t indices[kCandidates];
  float squared[kCandidates];
  const int found =
      surface_tree_.nearest(moved_point(p, pose), kCandidates, indices, squared, max_squared);
  if (found < 3) return;
  // The plane runs through the nearest surface point, the nearest on its row and the nearest on
  // a neighbouring row.
  const CloudPoint& nearest = (*previous_surfaces_)[indices[0]];
  const CloudPoint* same_row = nullptr;
  const CloudPoint* other_row = nullptr;
  for (int k = 1; k < found; ++k) {
    const CloudPoint& candidate = (*previous_surfaces_)[indices[k]];
    const int row_gap = std::abs(row_of(candidate) - row_of(nearest));
    if (row_gap == 0 && !same_row) same_row = &candidate;
    if (row_gap > 0 && row_gap <= 2 && !other_row) other_row = &candidate;
  }
  if (!same_row || !other_row) return;
  const Eigen::Vector3d a = position(nearest), b = position(*same_row), c = position(*other_row);
  Eigen::Vector3d normal = (b - a).cross(c - a);
  if (normal.norm() < 1e-6) return;
  normal.normalize();
  out.push_back({position(p), normal, -normal.dot(a), range_scale(p)});
}

void ScanToScanOdometry::solve(const Correspondences& matches, MatchKinds kinds,
                               const std::vector<int>& fixed_entries, double* pose) const {
  const std::size_t used = (kinds == MatchKinds::kPlanes ? 0 : matches.lines.size()) +
                           (kinds == MatchKinds::kLines ? 0 : matches.planes.size());
  if (used < 10) return;
  EulerRegistrationCost cost(matches, kinds, params_.huber_loss);
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  problem.AddResidualBlock(&cost, nullptr, pose);
  if (!fixed_entries.empty()) {
    problem.SetManifold(pose, new ceres::SubsetManifold(6, fixed_entries));
  }
  ceres::Solver::Summary summary;
  ceres::Solve(registration_solver_options(params_.solver_iterations), &problem, &summary);
}

OdometryResult ScanToScanOdometry::align(const FeatureSet& current, const Eigen::Isometry3d& guess,
                                         int iterations, Correspondences* final_matches) const {
  OdometryResult result;
  result.motion = guess;
  double pose[6];
  pose_to_euler_vector(guess, pose);
  Correspondences matches;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    const Eigen::Isometry3d before = euler_vector_to_pose(pose);
    find_edge_matches(*current.sharp, before, matches);
    find_plane_matches(*current.flat, before, matches);
    if (params_.mode == OdometryMode::kTwoStep) {
      solve(matches, MatchKinds::kPlanes, {2, 3, 4}, pose);  // ground planes: roll, pitch, z
      solve(matches, MatchKinds::kLines, {0, 1, 5}, pose);   // edges: yaw, x, y
    } else {
      solve(matches, MatchKinds::kBoth, {}, pose);
    }
    result.iterations = iteration + 1;
    const Eigen::Isometry3d change = before.inverse() * euler_vector_to_pose(pose);
    const double angle = Eigen::AngleAxisd(change.linear()).angle();
    // At least two searches: the first solve starts from stale matches.
    if (iteration >= 1 && angle < 1e-4 && change.translation().norm() < 1e-3) break;
  }
  result.edge_matches = static_cast<int>(matches.lines.size());
  result.plane_matches = static_cast<int>(matches.planes.size());
  result.registered = result.edge_matches + result.plane_matches >= 10;
  if (result.registered) result.motion = euler_vector_to_pose(pose);
  if (final_matches) *final_matches = std::move(matches);
  return result;
}

void ScanToScanOdometry::keep(const FeatureSet& current) {
  previous_corners_ = current.less_sharp;
  previous_surfaces_ = current.less_flat;
  run_both([&] { corner_tree_.build(previous_corners_); },
           [&] { surface_tree_.build(previous_surfaces_); });
}

OdometryResult ScanToScanOdometry::register_scan(const FeatureSet& current,
                                                 const Eigen::Isometry3d& guess) {
  OdometryResult result;
  result.motion = guess;
  if (previous_corners_ && previous_surfaces_) {
    // The first pair starts from no motion known, possibly far from the truth: more searches.
    const int iterations = first_pair_ ? 4 * params_.max_iterations : params_.max_iterations;
    first_pair_ = false;
    Correspondences matches;
    result = align(current, guess, iterations, &matches);
    if (result.registered) {
      result.information = correspondence_information(matches, result.motion, params_.huber_loss,
                                                      params_.residual_sigma);
      if (params_.follow_test_shift > 0.0) follow_test(current, guess, iterations, result);
    }
  }
  keep(current);
  return result;
}

// Where the scene fixes the motion along the direction of travel, a registration started from a
// guess moved along it comes back to the same motion; where it does not (smooth walls, whose
// rings and ring-made edges stay put in the sensor frame), the result moves with the guess, less
// what those features pull toward standing still. The information of those features says they fix
// the motion to centimetres; their follow does not.
void ScanToScanOdometry::follow_test(const FeatureSet& current, const Eigen::Isometry3d& guess,
                                     int iterations, OdometryResult& result) const {
  const double shift = params_.follow_test_shift;
  // Below a few centimetres a scan the guess's direction is its noise, not a direction of travel.
  constexpr double kMinTravel = 0.02;  // m
  if (guess.translation().norm() < kMinTravel) return;
  const Eigen::Vector3d direction = guess.translation().normalized();
  Eigen::Isometry3d shifted = guess;
  shifted.translation() += shift * direction;
  const OdometryResult other = align(current, shifted, iterations);
  if (!other.registered) return;
  result.follow = direction.dot(other.motion.translation() - result.motion.translation()) / shift;
  if (result.follow <= params_.follow_test_max &&
      !follows_from_still(current, guess, iterations, result))
    return;
  result.motion.translation() =
      held_along(result.motion.translation(), guess.translation(), direction);
  result.information =
      discounted_along(result.information, result.motion.linear().transpose() * direction, 0.0);
  result.held_direction = direction;
}

// Slowing down in a tunnel, the pull toward standing still can be as strong as the shift: the
// result falls back from the guess and a shifted guess falls back as far. Registered from standing
// still instead, a scan that sees its motion comes to the same result; a blind one stays near
// where it started.
bool ScanToScanOdometry::follows_from_still(const FeatureSet& current,
                                            const Eigen::Isometry3d& guess, int iterations,
                                            const OdometryResult& result) const {
  const Eigen::Vector3d direction = guess.translation().normalized();
  const double guessed = direction.dot(guess.translation());
  if (guessed >= params_.follow_test_still_speed * scan_period_) return false;
  // Only a scan that slows down: one that speeds up is not pulled toward standing still.
  if (direction.dot(result.motion.translation()) >= guessed) return false;
  Eigen::Isometry3d still = guess;
  still.translation() -= guessed * direction;
  const OdometryResult from_still = align(current, still, iterations);
  if (!from_still.registered) return false;
  const double kept =
      direction.dot(result.motion.translation() - from_still.motion.translation()) / guessed;
  return kept > params_.follow_test_max;
}

std::vector<OdometryResult> ScanToScanOdometry::align_each(
    const FeatureSet& current, const std::vector<Eigen::Isometry3d>& guesses) const {
  std::vector<OdometryResult> results;
  if (!previous_corners_ || !previous_surfaces_) return results;
  results.resize(guesses.size());
  for_chunks(guesses.size(), 1, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      results[i] = align(current, guesses[i], params_.max_iterations);
  });
  return results;
}

}  // namespace adaptive_lego_loam
