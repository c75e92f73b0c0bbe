#pragma once
// Every stage on one scan, as the offline tools run them and as the ROS nodes chain them: the
// ambient filter (image_projection), LidarOdometry (feature_association), LidarMapping
// (map_optimization, with transform fusion).

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/common/workers.h"
#include "adaptive_lego_loam/core/motion_sensors/motion_sensors.h"
#include "adaptive_lego_loam/core/odometry/lidar_odometry.h"
#include "adaptive_lego_loam/core/pipeline/lidar_mapping.h"

namespace adaptive_lego_loam {

struct FrameResult {
  int frame = 0;
  double stamp = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();           // mapped, sensor in map
  Eigen::Isometry3d odometry_pose = Eigen::Isometry3d::Identity();  // scan-to-scan alone
  bool valid_scan = true;  // false when the scan had no valid point (pose predicted)
  bool keyframe = false;
  bool loop_closed = false;
  bool motion_gated = false;  // scan-to-map started from the previous velocity (see MappingParams)
  std::optional<LoopDetection> loop;               // when loop closure was attempted on this scan
  std::optional<LocalizationStatus> localization;  // in localization mode
  bool deskewed_by_time_field = false;
  bool imu_used = false;    // the IMU's filter predicted this scan (de-skew, guess, priors)
  bool wheel_used = false;  // the wheel odometry did (on its own or in the IMU's filter)
  OdometryResult odometry;
  MapMatchResult mapping;
  int sharp = 0, less_sharp = 0, flat = 0, less_flat = 0;
  StageTimes times;
};

// The weak-direction prior the mapping gets from the ambient filter (none when turned off or
// when mu is unknown).
std::optional<WeakDirectionPrior> weak_direction_prior(const MappingParams& params,
                                                       const AmbientFilterResult& filtered);
// The same from the filter's degeneration and its (smoothed) mu, e.g. as a message carries them.
std::optional<WeakDirectionPrior> weak_direction_prior(const MappingParams& params,
                                                       const Degeneration& degeneration, double mu);
// The ambient filter's view of the scene for mapping: its weak direction and (smoothed) mu, when
// this scan's mu is known.
std::optional<SceneDegeneration> scene_degeneration(const AmbientFilterResult& filtered);
// The same from the filter's degeneration and its (smoothed) mu.
std::optional<SceneDegeneration> scene_degeneration(const Degeneration& degeneration, double mu);
// What the motion sensors learn from a mapped scan: the correspondences' information, along the
// scene's weak direction only in the share the scene constrains it (1 - mu).
Matrix6d sensor_feedback_information(const MapMatchResult& match,
                                     const std::optional<SceneDegeneration>& scene);
// How well the mapped pose is known (right perturbation [rotation, translation], sensor frame):
// the correspondences' information as the motion sensors learn from it, and the priors'.
Matrix6d pose_information(const MapMatchResult& match,
                          const std::optional<SceneDegeneration>& scene);
// The covariance published with a mapped pose (covariance_from_information of pose_information):
// zero on the scan that starts a map (`starts_map`), which defines the map frame; the unknown
// variance wherever a scan was not matched (the pose is the guess).
Matrix6d mapped_pose_covariance(const MapMatchResult& match, bool starts_map,
                                const std::optional<SceneDegeneration>& scene);
// Whether a mapped scan started the map: the first one mapping (not localizing) saw.
bool starts_map(const MappingOutput& mapped);
// The translation direction a matched scan's correspondences fix worst (sensor frame) and their
// 1-sigma along it (m; the scene's weak direction counted as above): degenerate beyond
// mapping.degenerate_translation_sigma, and then held or not by the motion sensors' prior or, where
// the odometry's follow test held the scan, by the motion model.
struct WeakestDirection {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  double sigma = 0.0;
  bool degenerate = false;
  bool held = false;
  // "the IMU", "the wheel odometry", "the IMU and the wheel odometry", "the motion model"
  std::string held_by;
};
WeakestDirection weakest_direction(const MapMatchResult& match,
                                   const std::optional<SceneDegeneration>& scene,
                                   const MappingParams& params);

class Pipeline {
 public:
  explicit Pipeline(const Config& config);
  // Localization on a saved map's keyframes from `start` (see LidarMapping).
  Pipeline(const Config& config, std::vector<Keyframe> map, const Eigen::Isometry3d& start);
  const FrameResult& process(const Scan& scan);
  // The same, with the next scan known: with more than one thread (set_threads), its ambient
  // filter and feature choice run on a second thread while this scan is registered, and the
  // searches are shared by idle threads; the poses are the same to the last bit. `next` must stay
  // unchanged until the next call, which must process it.
  const FrameResult& process(const Scan& scan, const Scan* next);
  // 1 (the default): everything on the caller's thread.
  void set_threads(int threads);
  int threads() const { return workers_ ? workers_->threads() : 1; }
  // The optional motion sensors' samples, as they arrive (before the scans they cover): a
  // sample's fault is counted, the sample dropped and the fault returned (for logging).
  std::optional<SampleFault> add_imu(const ImuSample& sample) { return motion_.add_imu(sample); }
  std::optional<SampleFault> add_wheel_odometry(const WheelOdometrySample& sample) {
    return motion_.add_wheel(sample);
  }
  // At the end of the input: finishes a loop closure still in progress (see LidarMapping).
  std::optional<LoopDetection> finish_loop_closure() { return mapping_.finish_loop_closure(); }

  const Config& config() const { return config_; }
  const AmbientFilterResult& filter_result() const { return filtered_; }
  const OdometryOutput& odometry_output() const { return odometry_out_; }
  const LidarMapping& mapping() const { return mapping_; }
  const MotionSensors& motion_sensors() const { return motion_; }
  const std::vector<Keyframe>& keyframes() const { return mapping_.keyframes(); }
  std::vector<Eigen::Isometry3d> trajectory() const { return mapping_.trajectory(); }

 private:
  Config config_;
  AmbientFilter filter_;
  MotionSensors motion_;
  LidarOdometry odometry_;
  LidarMapping mapping_;
  AmbientFilterResult filtered_;
  OdometryOutput odometry_out_;
  MappingOutput mapping_out_;
  int frames_ = 0;
  FrameResult result_;
  // The next scan's filter result and feature choice while they run ahead, and which scan it is
  // (with one thread, none: the odometry chooses the features itself).
  AmbientFilterResult filtered_ahead_;
  FeatureExtractor selector_;
  FeatureSelection selection_, selection_ahead_;
  bool selected_ = false;  // selection_ holds this scan's
  std::optional<std::pair<double, std::size_t>> ahead_of_;
  // Last: destroyed first, its threads joined before what they work on goes.
  std::unique_ptr<Workers> workers_;
};

}  // namespace adaptive_lego_loam
