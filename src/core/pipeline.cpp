#include "adaptive_lego_loam/core/pipeline.h"

#include <cmath>

#include "adaptive_lego_loam/core/motion_compensation.h"

namespace adaptive_lego_loam {

void TransformFusion::update_mapping(const Eigen::Isometry3d& odometry_pose,
                                     const Eigen::Isometry3d& map_pose) {
  correction_ = map_pose * odometry_pose.inverse();
}

Eigen::Isometry3d TransformFusion::fuse(const Eigen::Isometry3d& odometry_pose) const {
  return correction_ * odometry_pose;
}

Pipeline::Pipeline(const Config& config)
    : config_(config),
      filter_(config),
      extractor_(config.features),
      odometry_(config.odometry),
      local_map_(config.mapping),
      matcher_(config.mapping) {}

void Pipeline::deskew(const Scan& scan) {
  points_ = filtered_.segmentation.cloud.points;
  if (config_.sensor.deskewed || frames_ == 0) return;
  result_.deskewed_by_time_field =
      sweep_fractions(scan, points_, config_.sensor.scan_period, fractions_);
  // Constant velocity: the sweep moved as much as the last scan-to-scan motion.
  deskew_to_sweep_end(last_motion_, fractions_, points_);
}

void Pipeline::estimate_motion(FrameResult& result) {
  const Eigen::Isometry3d prediction =
      config_.odometry.constant_velocity ? last_motion_ : Eigen::Isometry3d::Identity();
  result.odometry = odometry_.register_scan(features_, prediction);
  const Eigen::Isometry3d motion = result.odometry.motion;
  odometry_pose_ = odometry_pose_ * motion;
  result.odometry_pose = odometry_pose_;
  Eigen::Isometry3d pose = map_pose_ * motion;

  if (config_.mapping.enabled && !keyframes_.empty()) {
    Stopwatch watch;
    local_map_.update(keyframes_, pose.translation(), map_version_);
    result.times.add("local_map", watch.lap_ms());
    const CloudPtr corners = voxel_filter(*features_.less_sharp, config_.mapping.corner_voxel);
    Cloud surface_points = *features_.less_flat;
    surface_points += *features_.outliers;
    const CloudPtr surfaces = voxel_filter(surface_points, config_.mapping.surface_voxel);
    std::optional<WeakDirectionPrior> prior;
    if (config_.mapping.weak_direction_prior > 0.0 && filtered_.degeneration.valid) {
      const Eigen::Vector2d& weak = filtered_.degeneration.weak_direction;
      prior = WeakDirectionPrior{Eigen::Vector3d(weak.x(), weak.y(), 0.0),
                                 config_.mapping.weak_direction_prior * filtered_.mu};
    }
    result.mapping = matcher_.match(*corners, *surfaces, local_map_, pose, prior);
    pose = result.mapping.pose;
    result.times.add("mapping", watch.lap_ms());
  }
  // The next scan is predicted with this scan's motion as mapping refined it.
  last_motion_ = map_pose_.inverse() * pose;
  map_pose_ = pose;
  fusion_.update_mapping(odometry_pose_, map_pose_);
  result.pose = map_pose_;
}

void Pipeline::update_keyframes(FrameResult& result) {
  bool add = keyframes_.empty();
  if (!add) {
    const Eigen::Isometry3d since = keyframes_.back().pose.inverse() * map_pose_;
    add = since.translation().norm() >= config_.mapping.keyframe_distance ||
          Eigen::AngleAxisd(since.linear()).angle() >=
              config_.mapping.keyframe_angle_deg * M_PI / 180.0;
  }
  if (add) {
    Keyframe keyframe;
    keyframe.index = static_cast<int>(keyframes_.size());
    keyframe.frame = frames_;
    keyframe.stamp = result.stamp;
    keyframe.pose = map_pose_;
    keyframe.corners = voxel_filter(*features_.less_sharp, config_.mapping.corner_voxel);
    Cloud surfaces = *features_.less_flat;
    surfaces += *features_.outliers;
    keyframe.surfaces = voxel_filter(surfaces, config_.mapping.surface_voxel);
    keyframe.outliers = features_.outliers;
    keyframes_.push_back(std::move(keyframe));
    result.keyframe = true;
  }
  const Keyframe& anchor = keyframes_.back();
  frame_anchors_.emplace_back(anchor.index, anchor.pose.inverse() * map_pose_);
}

const FrameResult& Pipeline::process(const Scan& scan) {
  result_ = FrameResult();
  result_.frame = frames_;
  result_.stamp = scan.stamp;
  Stopwatch watch;
  filter_.process(scan, filtered_);
  result_.times.append(filtered_.times());
  watch.lap_ms();
  result_.valid_scan = filtered_.segmentation.image.stats().projected > 0;

  deskew(scan);
  result_.times.add("deskew", watch.lap_ms());
  extractor_.extract(filtered_.segmentation.cloud, points_, features_);
  result_.sharp = static_cast<int>(features_.sharp->size());
  result_.less_sharp = static_cast<int>(features_.less_sharp->size());
  result_.flat = static_cast<int>(features_.flat->size());
  result_.less_flat = static_cast<int>(features_.less_flat->size());
  result_.times.add("features", watch.lap_ms());

  estimate_motion(result_);
  result_.times.add("odometry",
                    watch.lap_ms() - result_.times.get("local_map") - result_.times.get("mapping"));
  update_keyframes(result_);
  result_.times.add("keyframes", watch.lap_ms());
  ++frames_;
  return result_;
}

std::vector<Eigen::Isometry3d> Pipeline::trajectory() const {
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(frame_anchors_.size());
  for (const auto& [keyframe, relative] : frame_anchors_) {
    poses.push_back(keyframes_[keyframe].pose * relative);
  }
  return poses;
}

}  // namespace adaptive_lego_loam
