#pragma once
// Every stage on one scan, offline or behind the ROS nodes: the ambient filter, de-skewing,
// features, scan-to-scan odometry, scan-to-map matching with keyframes, and transform fusion.

#include <Eigen/Geometry>
#include <vector>

#include "adaptive_lego_loam/core/ambient_filter.h"
#include "adaptive_lego_loam/core/features.h"
#include "adaptive_lego_loam/core/keyframe.h"
#include "adaptive_lego_loam/core/mapping.h"
#include "adaptive_lego_loam/core/odometry.h"
#include "adaptive_lego_loam/core/params.h"
#include "adaptive_lego_loam/core/timing.h"

namespace adaptive_lego_loam {

// LeGO-LOAM's transformFusion: the high-rate odometry composed with the latest correction that
// mapping found (map pose = correction * odometry pose).
class TransformFusion {
 public:
  void update_mapping(const Eigen::Isometry3d& odometry_pose, const Eigen::Isometry3d& map_pose);
  Eigen::Isometry3d fuse(const Eigen::Isometry3d& odometry_pose) const;
  const Eigen::Isometry3d& correction() const { return correction_; }

 private:
  Eigen::Isometry3d correction_ = Eigen::Isometry3d::Identity();
};

struct FrameResult {
  int frame = 0;
  double stamp = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();           // mapped, sensor in map
  Eigen::Isometry3d odometry_pose = Eigen::Isometry3d::Identity();  // scan-to-scan alone
  bool valid_scan = true;  // false when the scan had no valid point (pose predicted)
  bool keyframe = false;
  bool deskewed_by_time_field = false;
  OdometryResult odometry;
  MapMatchResult mapping;
  int sharp = 0, less_sharp = 0, flat = 0, less_flat = 0;
  StageTimes times;
};

class Pipeline {
 public:
  explicit Pipeline(const Config& config);
  const FrameResult& process(const Scan& scan);

  const Config& config() const { return config_; }
  const AmbientFilterResult& filter_result() const { return filtered_; }
  const FeatureSet& features() const { return features_; }
  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  const LocalMap& local_map() const { return local_map_; }
  // Every frame's pose, re-derived from its keyframe so that later keyframe corrections apply.
  std::vector<Eigen::Isometry3d> trajectory() const;

 private:
  void deskew(const Scan& scan);
  void estimate_motion(FrameResult& result);
  void update_keyframes(FrameResult& result);

  Config config_;
  AmbientFilter filter_;
  FeatureExtractor extractor_;
  ScanToScanOdometry odometry_;
  LocalMap local_map_;
  ScanToMapMatcher matcher_;
  TransformFusion fusion_;

  AmbientFilterResult filtered_;
  std::vector<ScanPoint> points_;  // segmented points, de-skewed
  std::vector<float> fractions_;
  FeatureSet features_;
  std::vector<Keyframe> keyframes_;
  int map_version_ = 0;

  int frames_ = 0;
  Eigen::Isometry3d last_motion_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d odometry_pose_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d map_pose_ = Eigen::Isometry3d::Identity();
  // Per frame: the keyframe it hangs from and its pose relative to that keyframe.
  std::vector<std::pair<int, Eigen::Isometry3d>> frame_anchors_;
  FrameResult result_;
};

}  // namespace adaptive_lego_loam
