#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"

#include <cmath>

#include "adaptive_lego_loam/core/odometry/deskew.h"

namespace adaptive_lego_loam {

LidarOdometry::LidarOdometry(const SensorParams& sensor, const FeatureParams& features,
                             const OdometryParams& odometry)
    : sensor_(sensor), params_(odometry), extractor_(features), registration_(odometry) {}

void LidarOdometry::process(const SegmentedCloud& cloud, bool has_time, OdometryOutput& out) {
  Stopwatch watch;
  out.times.clear();
  points_ = cloud.points;
  outliers_ = cloud.outliers;
  out.deskewed_by_time_field = false;
  if (!sensor_.deskewed && !first_) {
    // Constant velocity: the sweep moved as much as the last scan-to-scan motion. CloudInfo's
    // orientation is LeGO-LOAM's clockwise angle, the negated azimuth.
    const double start_azimuth = -cloud.info.start_orientation;
    for (std::vector<ScanPoint>* points : {&points_, &outliers_}) {
      out.deskewed_by_time_field =
          sweep_fractions(*points, has_time, start_azimuth, sensor_.scan_period, fractions_);
      deskew_to_sweep_end(last_motion_, fractions_, *points);
    }
  }
  out.times.add("deskew", watch.lap_ms());
  extractor_.extract(cloud, points_, outliers_, out.features);
  out.times.add("features", watch.lap_ms());

  const Eigen::Isometry3d prediction =
      params_.constant_velocity ? last_motion_ : Eigen::Isometry3d::Identity();
  // The first pair: no motion is known yet, and the sensor may already be moving fast.
  const bool first_pair = scans_ == 1 && params_.start_search_max_speed > 0.0;
  out.odometry = first_pair ? registration_.register_scan(out.features, start_guesses())
                            : registration_.register_scan(out.features, prediction);
  if (!plausible_motion(out.odometry.motion, params_, sensor_.scan_period)) {
    out.odometry.motion = prediction;
    out.odometry.rejected = true;
  }
  last_motion_ = out.odometry.motion;
  pose_ = pose_ * out.odometry.motion;
  out.pose = pose_;
  first_ = false;
  ++scans_;
  out.times.add("odometry", watch.lap_ms());
}

std::vector<Eigen::Isometry3d> LidarOdometry::start_guesses() const {
  std::vector<Eigen::Isometry3d> guesses;
  const double reach = params_.start_search_max_speed * sensor_.scan_period;
  for (double x = 0.0; x <= reach + 1e-9; x += params_.start_search_step) {
    Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
    guess.translation().x() = x;
    guesses.push_back(guess);
  }
  return guesses;
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
