#pragma once
// LeGO-LOAM's featureAssociation on the core: de-skewing of the segmented cloud, feature
// extraction and scan-to-scan odometry. Fed by the ambient filter's segmented cloud; feeds
// LidarMapping. The pipeline and the feature_association node run this same class.

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/features.h"
#include "adaptive_lego_loam/core/odometry.h"
#include "adaptive_lego_loam/core/params.h"
#include "adaptive_lego_loam/core/segmentation.h"
#include "adaptive_lego_loam/core/timing.h"

namespace adaptive_lego_loam {

struct OdometryOutput {
  FeatureSet features;  // de-skewed to the end of the sweep
  OdometryResult odometry;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // in the odometry frame
  bool deskewed_by_time_field = false;
  StageTimes times;
};

class LidarOdometry {
 public:
  LidarOdometry(const SensorParams& sensor, const FeatureParams& features,
                const OdometryParams& odometry);
  // `has_time`: whether the cloud's points carry their time in the sweep.
  void process(const SegmentedCloud& cloud, bool has_time, OdometryOutput& out);
  // The last scan's motion as mapping refined it (the previous scan's pose to the last one's in
  // the map): replaces the odometry's own estimate as the constant-velocity model that de-skews
  // and predicts the next scan. Mapping's is far better on 16-beam sensors.
  void use_mapped_motion(const Eigen::Isometry3d& motion) { last_motion_ = motion; }

 private:
  SensorParams sensor_;
  OdometryParams params_;
  FeatureExtractor extractor_;
  ScanToScanOdometry registration_;
  std::vector<ScanPoint> points_, outliers_;
  std::vector<float> fractions_;
  bool first_ = true;
  Eigen::Isometry3d last_motion_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
};

}  // namespace adaptive_lego_loam
