#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"

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
  out.odometry = registration_.register_scan(out.features, prediction);
  last_motion_ = out.odometry.motion;
  pose_ = pose_ * out.odometry.motion;
  out.pose = pose_;
  first_ = false;
  out.times.add("odometry", watch.lap_ms());
}

bool uses_mapped_motion(const OdometryParams& odometry, const MappingParams& mapping) {
  return odometry.motion_from_mapping && mapping.enabled;
}

}  // namespace adaptive_lego_loam
