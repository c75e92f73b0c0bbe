#include "adaptive_lego_loam/core/odometry.h"

#include <cmath>

#include "adaptive_lego_loam/core/residuals.h"

namespace adaptive_lego_loam {

struct ScanToScanOdometry::Matches {
  struct Line {
    Eigen::Vector3d point, a, b;
  };
  struct Plane {
    Eigen::Vector3d point, normal;
    double offset;
  };
  std::vector<Line> lines;
  std::vector<Plane> planes;
};

namespace {

constexpr int kCandidates = 15;

Eigen::Vector3d position(const CloudPoint& p) {
  return p.getVector3fMap().cast<double>();
}

int row_of(const CloudPoint& p) {
  return static_cast<int>(std::lround(p.intensity));
}

// The feature point moved into the previous scan's frame by the current estimate.
CloudPoint moved_point(const CloudPoint& p, const double* pose) {
  const Eigen::Vector3d moved = apply_euler_pose(pose, position(p));
  CloudPoint q = p;
  q.getVector3fMap() = moved.cast<float>();
  return q;
}

}  // namespace

ScanToScanOdometry::ScanToScanOdometry(const OdometryParams& params) : params_(params) {}

void ScanToScanOdometry::reset() {
  previous_corners_.reset();
  first_pair_ = true;
  previous_surfaces_.reset();
}

void ScanToScanOdometry::find_edge_matches(const Cloud& sharp, const double* pose,
                                           Matches& matches) {
  matches.lines.clear();
  if (previous_corners_->size() < 2) return;
  const float max_squared =
      static_cast<float>(params_.max_match_distance * params_.max_match_distance);
  uint32_t indices[kCandidates];
  float squared[kCandidates];
  for (const CloudPoint& p : sharp) {
    const int found =
        corner_tree_.nearest(moved_point(p, pose).getVector3fMap(), kCandidates, indices, squared);
    if (found < 2 || squared[0] > max_squared) continue;
    // The line runs through the nearest edge point and the nearest one on a neighbouring row.
    const CloudPoint& nearest = (*previous_corners_)[indices[0]];
    for (int k = 1; k < found; ++k) {
      const CloudPoint& other = (*previous_corners_)[indices[k]];
      const int row_gap = std::abs(row_of(other) - row_of(nearest));
      if (squared[k] > max_squared || row_gap == 0 || row_gap > 2) continue;
      matches.lines.push_back({position(p), position(nearest), position(other)});
      break;
    }
  }
}

void ScanToScanOdometry::find_plane_matches(const Cloud& flat, const double* pose,
                                            Matches& matches) {
  matches.planes.clear();
  if (previous_surfaces_->size() < 3) return;
  const float max_squared =
      static_cast<float>(params_.max_match_distance * params_.max_match_distance);
  uint32_t indices[kCandidates];
  float squared[kCandidates];
  for (const CloudPoint& p : flat) {
    const int found =
        surface_tree_.nearest(moved_point(p, pose).getVector3fMap(), kCandidates, indices, squared);
    if (found < 3 || squared[0] > max_squared) continue;
    // The plane runs through the nearest surface point, the nearest on its row and the nearest
    // on a neighbouring row.
    const CloudPoint& nearest = (*previous_surfaces_)[indices[0]];
    const CloudPoint* same_row = nullptr;
    const CloudPoint* other_row = nullptr;
    for (int k = 1; k < found; ++k) {
      if (squared[k] > max_squared) break;
      const CloudPoint& candidate = (*previous_surfaces_)[indices[k]];
      const int row_gap = std::abs(row_of(candidate) - row_of(nearest));
      if (row_gap == 0 && !same_row) same_row = &candidate;
      if (row_gap > 0 && row_gap <= 2 && !other_row) other_row = &candidate;
    }
    if (!same_row || !other_row) continue;
    const Eigen::Vector3d a = position(nearest), b = position(*same_row), c = position(*other_row);
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() < 1e-6) continue;
    normal.normalize();
    matches.planes.push_back({position(p), normal, -normal.dot(a)});
  }
}

void ScanToScanOdometry::solve(const Matches& matches, bool use_edges, bool use_planes,
                               const std::vector<int>& fixed_entries, double* pose) const {
  ceres::Problem problem;
  // The problem owns the loss and deletes it once however many blocks share it.
  ceres::LossFunction* loss = new ceres::HuberLoss(params_.huber_loss);
  int residuals = 0;
  if (use_edges) {
    for (const auto& line : matches.lines) {
      problem.AddResidualBlock(EulerPointToLine::create(line.point, line.a, line.b), loss, pose);
      ++residuals;
    }
  }
  if (use_planes) {
    for (const auto& plane : matches.planes) {
      problem.AddResidualBlock(EulerPointToPlane::create(plane.point, plane.normal, plane.offset),
                               loss, pose);
      ++residuals;
    }
  }
  if (residuals < 10) {
    if (residuals == 0) delete loss;
    return;
  }
  if (!fixed_entries.empty()) {
    problem.SetManifold(pose, new ceres::SubsetManifold(6, fixed_entries));
  }
  ceres::Solver::Summary summary;
  ceres::Solve(registration_solver_options(params_.solver_iterations), &problem, &summary);
}

OdometryResult ScanToScanOdometry::register_scan(const FeatureSet& current,
                                                 const Eigen::Isometry3d& guess) {
  OdometryResult result;
  result.motion = guess;
  if (previous_corners_ && previous_surfaces_) {
    double pose[6];
    pose_to_euler_vector(guess, pose);
    Matches matches;
    // The first pair starts from no motion at all, possibly far from the truth: more searches.
    const int iterations = first_pair_ ? 4 * params_.max_iterations : params_.max_iterations;
    first_pair_ = false;
    for (int iteration = 0; iteration < iterations; ++iteration) {
      const Eigen::Isometry3d before = euler_vector_to_pose(pose);
      find_edge_matches(*current.sharp, pose, matches);
      find_plane_matches(*current.flat, pose, matches);
      if (params_.mode == OdometryMode::kTwoStep) {
        solve(matches, false, true, {2, 3, 4}, pose);  // ground planes: roll, pitch, z
        solve(matches, true, false, {0, 1, 5}, pose);  // edges: yaw, x, y
      } else {
        solve(matches, true, true, {}, pose);
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
  }
  previous_corners_ = current.less_sharp;
  previous_surfaces_ = current.less_flat;
  corner_tree_.build(previous_corners_);
  surface_tree_.build(previous_surfaces_);
  return result;
}

}  // namespace adaptive_lego_loam
