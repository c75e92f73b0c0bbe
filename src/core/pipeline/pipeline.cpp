#include "adaptive_lego_loam/core/pipeline/pipeline.h"

#include <stdexcept>

#include "adaptive_lego_loam/core/odometry/observability.h"

namespace adaptive_lego_loam {

std::optional<WeakDirectionPrior> weak_direction_prior(const MappingParams& params,
                                                       const Degeneration& degeneration,
                                                       double mu) {
  if (params.weak_direction_prior <= 0.0 || !degeneration.valid) return std::nullopt;
  const Eigen::Vector2d& weak = degeneration.weak_direction;
  return WeakDirectionPrior{Eigen::Vector3d(weak.x(), weak.y(), 0.0),
                            params.weak_direction_prior * mu};
}

std::optional<WeakDirectionPrior> weak_direction_prior(const MappingParams& params,
                                                       const AmbientFilterResult& filtered) {
  return weak_direction_prior(params, filtered.degeneration, filtered.mu);
}

std::optional<SceneDegeneration> scene_degeneration(const AmbientFilterResult& filtered) {
  return scene_degeneration(filtered.degeneration, filtered.mu);
}

std::optional<SceneDegeneration> scene_degeneration(const Degeneration& degeneration, double mu) {
  if (!degeneration.valid) return std::nullopt;
  const Eigen::Vector2d& weak = degeneration.weak_direction;
  return SceneDegeneration{Eigen::Vector3d(weak.x(), weak.y(), 0.0), mu};
}

Matrix6d sensor_feedback_information(const MapMatchResult& match,
                                     const std::optional<SceneDegeneration>& scene) {
  if (!scene) return match.information;
  return discounted_along(match.information, scene->weak_direction, 1.0 - scene->mu);
}

Matrix6d pose_information(const MapMatchResult& match,
                          const std::optional<SceneDegeneration>& scene) {
  return sensor_feedback_information(match, scene) + match.prior_information;
}

Matrix6d mapped_pose_covariance(const MapMatchResult& match, bool starts_map,
                                const std::optional<SceneDegeneration>& scene) {
  if (starts_map) return Matrix6d::Zero();
  return covariance_from_information(match.matched ? pose_information(match, scene)
                                                   : Matrix6d::Zero());
}

bool starts_map(const MappingOutput& mapped) {
  return !mapped.motion && !mapped.localization;
}

namespace {

std::string prior_sources(const MapMatchResult& match) {
  if (match.prior_from_imu && match.prior_from_wheel) return "the IMU and the wheel odometry";
  if (match.prior_from_imu) return "the IMU";
  if (match.prior_from_wheel) return "the wheel odometry";
  return "the motion sensors";
}

}  // namespace

WeakestDirection weakest_direction(const MapMatchResult& match,
                                   const std::optional<SceneDegeneration>& scene,
                                   const MappingParams& params) {
  const Observability seen = observability(sensor_feedback_information(match, scene));
  WeakestDirection weakest;
  weakest.direction = seen.weakest_direction();
  weakest.sigma = seen.weakest_sigma();
  weakest.degenerate = !(weakest.sigma <= params.degenerate_translation_sigma);
  weakest.held = weakest.degenerate && (match.motion_prior || match.odometry_held);
  if (weakest.held)
    weakest.held_by = match.motion_prior ? prior_sources(match) : "the motion model";
  return weakest;
}

Pipeline::Pipeline(const Config& config)
    : config_(config),
      filter_(config),
      motion_(config),
      odometry_(config.sensor, config.features, config.odometry),
      mapping_(config),
      selector_(config.features) {}

Pipeline::Pipeline(const Config& config, std::vector<Keyframe> map, const Eigen::Isometry3d& start)
    : config_(config),
      filter_(config),
      motion_(config),
      odometry_(config.sensor, config.features, config.odometry),
      mapping_(config, std::move(map), start),
      selector_(config.features) {}

void Pipeline::set_threads(int threads) {
  if (ahead_of_) throw std::logic_error("Pipeline: threads changed while a scan runs ahead");
  workers_ = threads > 1 ? std::make_unique<Workers>(threads) : nullptr;
}

const FrameResult& Pipeline::process(const Scan& scan) {
  return process(scan, nullptr);
}

const FrameResult& Pipeline::process(const Scan& scan, const Scan* next) {
  result_ = FrameResult();
  result_.frame = frames_++;
  result_.stamp = scan.stamp;
  if (ahead_of_) {
    const std::pair<double, std::size_t> announced = *ahead_of_;
    ahead_of_.reset();
    workers_->wait_background();
    if (announced != std::make_pair(scan.stamp, scan.points.size()))
      throw std::logic_error("Pipeline: the scan processed is not the one announced as next");
    std::swap(filtered_, filtered_ahead_);
    std::swap(selection_, selection_ahead_);
    selected_ = true;
  } else {
    filter_.process(scan, filtered_);
    selected_ = false;
  }
  if (next && workers_) {
    ahead_of_ = std::make_pair(next->stamp, next->points.size());
    workers_->start_background([this, next] {
      filter_.process(*next, filtered_ahead_);
      selector_.select(filtered_ahead_.segmentation.cloud, selection_ahead_);
    });
  }
  const UseWorkers use_workers(workers_.get());
  result_.times.append(filtered_.times());
  result_.valid_scan = filtered_.segmentation.image.stats().projected > 0;

  // The motion sensors, when there are any: LiDAR-only otherwise, as if they did not exist.
  const MotionPrediction* sensors = nullptr;
  if (motion_.active()) {
    Stopwatch watch;
    const MotionPrediction& prediction = motion_.predict(scan.stamp, config_.sensor.scan_period);
    if (!prediction.empty()) sensors = &prediction;
    result_.times.add("motion_sensors", watch.lap_ms());
    result_.imu_used = motion_.status().imu_in_use;
    result_.wheel_used = motion_.status().wheel_in_use;
  }

  odometry_.process(filtered_.segmentation.cloud, scan.has_time, odometry_out_, sensors,
                    selected_ ? &selection_ : nullptr);
  result_.times.append(odometry_out_.times);
  result_.odometry = odometry_out_.odometry;
  result_.odometry_pose = odometry_out_.pose;
  result_.deskewed_by_time_field = odometry_out_.deskewed_by_time_field;
  const FeatureSet& features = odometry_out_.features;
  result_.sharp = static_cast<int>(features.sharp->size());
  result_.less_sharp = static_cast<int>(features.less_sharp->size());
  result_.flat = static_cast<int>(features.flat->size());
  result_.less_flat = static_cast<int>(features.less_flat->size());

  const std::optional<SceneDegeneration> scene = scene_degeneration(filtered_);
  mapping_.process(features, odometry_out_.pose, scan.stamp,
                   weak_direction_prior(config_.mapping, filtered_), mapping_out_, sensors, scene,
                   odometry_out_.odometry.held_direction);
  if (motion_.active()) {
    Stopwatch watch;
    // What the LiDAR saw of this scan's motion teaches the sensors (biases, scale, velocity).
    const bool mapped = mapping_out_.match.matched && mapping_out_.motion;
    motion_.update(mapped ? mapping_out_.motion : std::nullopt,
                   sensor_feedback_information(mapping_out_.match, scene),
                   mapping_out_.match.motion_prior);
    result_.times.add("motion_sensors", watch.lap_ms());
  }
  if (uses_mapped_motion(config_.odometry, config_.mapping) && mapping_out_.motion) {
    odometry_.use_mapped_motion(*mapping_out_.motion);
  }
  result_.times.append(mapping_out_.times);
  result_.mapping = mapping_out_.match;
  result_.pose = mapping_out_.pose;
  result_.keyframe = mapping_out_.keyframe;
  result_.motion_gated = mapping_out_.motion_gated;
  result_.loop = mapping_out_.loop;
  result_.loop_closed = mapping_out_.loop_closed;
  result_.localization = mapping_out_.localization;
  return result_;
}

}  // namespace adaptive_lego_loam
