#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"

#include <cmath>

#include "adaptive_lego_loam/core/odometry/covariance_propagation.h"
#include "adaptive_lego_loam/core/odometry/deskew.h"
#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/core/odometry/start_search.h"

namespace adaptive_lego_loam {

LidarOdometry::LidarOdometry(const SensorParams& sensor, const FeatureParams& features,
                             const OdometryParams& odometry)
    : sensor_(sensor),
      params_(odometry),
      extractor_(features),
      registration_(odometry, sensor.beam_angles_deg, sensor.scan_period) {}

void LidarOdometry::process(const SegmentedCloud& cloud, bool has_time, OdometryOutput& out,
                            const MotionPrediction* sensors, const FeatureSelection* selection) {
  Stopwatch watch;
  out.times.clear();
  points_ = cloud.points;
  outliers_ = cloud.outliers;
  out.deskewed_by_time_field = false;
  const bool measured_sweep = sensors && sensors->sweep;
  if (!sensor_.deskewed && (!first_ || measured_sweep)) {
    // As the motion sensors measured the sweep, else at constant velocity: the sweep moved as
    // much as the last scan-to-scan motion. CloudInfo's orientation is LeGO-LOAM's clockwise
    // angle, the negated azimuth.
    const double start_azimuth = -cloud.info.start_orientation;
    for (std::vector<ScanPoint>* points : {&points_, &outliers_}) {
      out.deskewed_by_time_field =
          sweep_fractions(*points, has_time, start_azimuth, sensor_.scan_period, fractions_);
      if (measured_sweep) {
        deskew_to_sweep_end(*sensors->sweep, fractions_, *points);
      } else {
        deskew_to_sweep_end(last_motion_, fractions_, *points);
      }
    }
  }
  out.times.add("deskew", watch.lap_ms());
  if (selection) {
    extractor_.assemble(*selection, points_, outliers_, out.features);
    out.times.add("features", watch.lap_ms() + selection->ms);
  } else {
    extractor_.extract(cloud, points_, outliers_, out.features);
    out.times.add("features", watch.lap_ms());
  }

  const Eigen::Isometry3d prediction = sensors && sensors->motion  ? sensors->motion->motion
                                       : params_.constant_velocity ? last_motion_
                                                                   : Eigen::Isometry3d::Identity();
  // The first pair: no motion is known yet, and the sensor may already be moving fast.
  const bool start_search = params_.start_search_max_speed > 0.0;
  if (scans_ == 1 && start_search) {
    out.odometry = registration_.register_scan(
        out.features,
        start_motion(out.features, *start_points(points_, cloud.info.ground_flag, outliers_)));
    previous_start_points_.reset();
  } else {
    out.odometry = registration_.register_scan(out.features, prediction);
  }
  if (scans_ == 0 && start_search) {
    previous_start_points_ = start_points(points_, cloud.info.ground_flag, outliers_);
  }
  if (!plausible_motion(out.odometry.motion, params_, sensor_.scan_period)) {
    out.odometry.motion = prediction;
    out.odometry.rejected = true;
  }
  last_motion_ = out.odometry.motion;
  if (scans_ > 0) {
    const bool measured = out.odometry.registered && !out.odometry.rejected;
    pose_covariance_ = compose_covariance(
        pose_covariance_, out.odometry.motion,
        covariance_from_information(measured ? out.odometry.information : Matrix6d::Zero()));
  }
  pose_ = pose_ * out.odometry.motion;
  out.pose = pose_;
  out.pose_covariance = pose_covariance_;
  first_ = false;
  ++scans_;
  out.times.add("odometry", watch.lap_ms());
}

Eigen::Isometry3d LidarOdometry::start_motion(const FeatureSet& features,
                                              const Cloud& current) const {
  // Within the scans' spacing of points on a surface at tens of metres, and under the 2 m of
  // the repeating posts' aliases.
  constexpr float kOverlapRadius = 0.25f;  // m
  const std::vector<Eigen::Isometry3d> guesses = start_guesses(params_, sensor_.scan_period);
  const std::vector<OdometryResult> candidates = registration_.align_each(features, guesses);
  PointKdTree previous;
  if (previous_start_points_) previous.build(previous_start_points_);
  Eigen::Isometry3d best = guesses.front();
  double best_overlap = -1.0;
  for (const OdometryResult& candidate : candidates) {
    if (!candidate.registered) continue;
    const double fit = overlap_area(previous, current, candidate.motion, kOverlapRadius);
    if (fit > best_overlap) {
      best_overlap = fit;
      best = candidate.motion;
    }
  }
  return best;
}

bool plausible_motion(const Eigen::Isometry3d& motion, const OdometryParams& odometry,
                      double scan_period) {
  if (!motion.matrix().allFinite()) return false;
  const double distance = motion.translation().norm();
  const double turn_deg = Eigen::AngleAxisd(motion.linear()).angle() * 180.0 / M_PI;
  if (odometry.max_speed > 0.0 && distance > odometry.max_speed * scan_period) return false;
  return odometry.max_turn_rate_deg <= 0.0 || turn_deg <= odometry.max_turn_rate_deg * scan_period;
}

bool uses_mapped_motion(const OdometryParams& odometry, const MappingParams& mapping) {
  return odometry.motion_from_mapping && mapping.enabled;
}

}  // namespace adaptive_lego_loam
