#pragma once
// Scan-to-scan odometry (LeGO-LOAM's featureAssociation) with Ceres: the current scan's sharp
// edges against lines of the previous scan's edges, its flat (ground) surfaces against planes of
// the previous scan's surfaces. Two solves, selectable: LeGO-LOAM's two steps (planes fix z, roll
// and pitch; then edges fix x, y and yaw) or one joint 6-DoF solve.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/odometry/feature_extraction.h"
#include "adaptive_lego_loam/core/spatial/kdtree.h"

namespace adaptive_lego_loam {

struct Correspondences;  // core/odometry/residuals.h
struct LineMatch;
struct PlaneMatch;
enum class MatchKinds : int;  // core/residuals.h

struct OdometryResult {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  // current scan in previous' frame
  int edge_matches = 0;
  int plane_matches = 0;
  int iterations = 0;
  bool registered = false;  // false for the first scan or when too few matches were found
  // The registration's motion was implausible (OdometryParams::max_speed, max_turn_rate_deg) and
  // `motion` is the prediction instead.
  bool rejected = false;
  // What the last correspondences say of the motion (correspondence_information over
  // OdometryParams::residual_sigma, at `motion`, in the current scan's frame); zero unless
  // registered. Only register_scan fills it.
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  // The follow test (OdometryParams::follow_test_shift) found the scan blind along this direction
  // (unit, in the previous scan's frame, as `motion`'s translation): `motion` keeps the guess's
  // translation along it, and `information` says nothing about it.
  std::optional<Eigen::Vector3d> held_direction;
  double follow = 0.0;  // how far the result moved with the shifted guess (share of the shift)
};

class ScanToScanOdometry {
 public:
  // `beam_angles_deg` (the sensor's, ascending) set the ring spacing of the range weighting
  // (OdometryParams::range_weight_fit_error); without them every correspondence weighs the same.
  // `scan_period` (s) turns the follow test's speed into travel a scan.
  explicit ScanToScanOdometry(const OdometryParams& params,
                              const std::vector<double>& beam_angles_deg = {},
                              double scan_period = 0.1);
  // Registers `current` against the previous scan's features, starting from `guess` (the motion
  // from the previous scan to this one); then keeps `current` as the previous scan.
  OdometryResult register_scan(const FeatureSet& current, const Eigen::Isometry3d& guess);
  // Registers `current` against the previous scan from each of `guesses` in turn, each with the
  // usual searches; nothing is kept (empty before a previous scan exists).
  std::vector<OdometryResult> align_each(const FeatureSet& current,
                                         const std::vector<Eigen::Isometry3d>& guesses) const;
  void reset();

 private:
  // Registration from `guess` with up to `iterations` correspondence searches; no state changes.
  // The last correspondences go to `final_matches` when given.
  OdometryResult align(const FeatureSet& current, const Eigen::Isometry3d& guess, int iterations,
                       Correspondences* final_matches = nullptr) const;
  void keep(const FeatureSet& current);
  // OdometryParams::follow_test_shift on `result`, registered from `guess`.
  void follow_test(const FeatureSet& current, const Eigen::Isometry3d& guess, int iterations,
                   OdometryResult& result) const;
  // OdometryParams::follow_test_still_speed: `result` (from `guess`) slowed down, and registered
  // from standing still `current` ends more than follow_test_max of the guessed travel short of it.
  bool follows_from_still(const FeatureSet& current, const Eigen::Isometry3d& guess, int iterations,
                          const OdometryResult& result) const;
  // Each point's correspondence (when it has one), in the points' order.
  void find_edge_matches(const Cloud& sharp, const Eigen::Isometry3d& pose,
                         Correspondences& matches) const;
  void find_edge_match(const CloudPoint& p, const Eigen::Isometry3d& pose, float max_squared,
                       std::vector<LineMatch>& out) const;
  void find_plane_matches(const Cloud& flat, const Eigen::Isometry3d& pose,
                          Correspondences& matches) const;
  void find_plane_match(const CloudPoint& p, const Eigen::Isometry3d& pose, float max_squared,
                        std::vector<PlaneMatch>& out) const;
  // One Ceres solve over the given correspondence kinds with the listed entries of the Euler
  // 6-vector held fixed.
  void solve(const Correspondences& matches, MatchKinds kinds,
             const std::vector<int>& fixed_entries, double* pose) const;
  // The range weighting's constants of a row: the fit error's growth with range (rad), and the
  // root weight of a point 10 m away.
  struct RangeWeighting {
    double blur_rad;
    double reference;
  };
  double root_weight(const RangeWeighting& row, double range) const;
  // The residual scale of a correspondence of feature point `p` (its row in the intensity).
  double range_scale(const CloudPoint& p) const;

  OdometryParams params_;
  double scan_period_;                           // s
  std::vector<RangeWeighting> range_weighting_;  // per row; empty: no range weighting
  bool first_pair_ = true;
  CloudPtr previous_corners_, previous_surfaces_;
  PointKdTree corner_tree_, surface_tree_;
};

}  // namespace adaptive_lego_loam
