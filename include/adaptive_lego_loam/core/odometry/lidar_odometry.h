#pragma once
// LeGO-LOAM's featureAssociation on the core: de-skewing of the segmented cloud, feature
// extraction and scan-to-scan odometry. Fed by the ambient filter's segmented cloud; feeds
// LidarMapping. The pipeline and the feature_association node run this same class.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"
#include "adaptive_lego_loam/core/odometry/feature_extraction.h"
#include "adaptive_lego_loam/core/odometry/scan_to_scan.h"

namespace adaptive_lego_loam {

struct OdometryOutput {
  FeatureSet features;  // de-skewed to the end of the sweep
  OdometryResult odometry;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // in the odometry frame
  // Of `pose` (covariance_propagation.h): each registration's covariance added to the last
  // pose's; a motion not registered (or rejected) adds the unknown variance of
  // covariance_from_information.
  Eigen::Matrix<double, 6, 6> pose_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  bool deskewed_by_time_field = false;
  StageTimes times;
};

class LidarOdometry {
 public:
  LidarOdometry(const SensorParams& sensor, const FeatureParams& features,
                const OdometryParams& odometry);
  // `has_time`: whether the cloud's points carry their time in the sweep. `sensors`: the motion
  // sensors' prediction of this scan, if any: its sweep de-skews, its motion is the guess.
  // `selection`: the cloud's features chosen ahead (FeatureExtractor::select), if they were.
  void process(const SegmentedCloud& cloud, bool has_time, OdometryOutput& out,
               const MotionPrediction* sensors = nullptr,
               const FeatureSelection* selection = nullptr);
  // The last scan's motion as mapping refined it (MappingOutput::motion) replaces the odometry's
  // own estimate as the constant-velocity model that de-skews and predicts the next scan:
  // mapping's is far better on 16-beam sensors. Call it only when uses_mapped_motion().
  void use_mapped_motion(const Eigen::Isometry3d& motion) { last_motion_ = motion; }

 private:
  SensorParams sensor_;
  OdometryParams params_;
  FeatureExtractor extractor_;
  ScanToScanOdometry registration_;
  std::vector<ScanPoint> points_, outliers_;
  std::vector<float> fractions_;
  bool first_ = true;
  int scans_ = 0;  // processed so far
  // The first pair's guess (core/odometry/start_search.h): of the registrations from each start
  // guess, the one that lays most of `current`'s non-ground surface onto the first scan's.
  Eigen::Isometry3d start_motion(const FeatureSet& features, const Cloud& current) const;
  CloudPtr previous_start_points_;  // the first scan's non-ground points, until the second
  Eigen::Isometry3d last_motion_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
  Eigen::Matrix<double, 6, 6> pose_covariance_ = Eigen::Matrix<double, 6, 6>::Zero();
};

// Whether `motion`, over one scan period, is finite and within the odometry's max_speed and
// max_turn_rate_deg.
bool plausible_motion(const Eigen::Isometry3d& motion, const OdometryParams& odometry,
                      double scan_period);

// Whether the odometry takes its motion model from mapping (LidarOdometry::use_mapped_motion).
bool uses_mapped_motion(const OdometryParams& odometry, const MappingParams& mapping);

}  // namespace adaptive_lego_loam
