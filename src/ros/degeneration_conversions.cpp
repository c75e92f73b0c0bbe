#include "adaptive_lego_loam/ros/degeneration_conversions.h"

#include <algorithm>
#include <cstdio>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/ros/arrow_marker.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

constexpr double kArrowMinLength = 2.0;  // m, at mu = 0
constexpr double kArrowMuLength = 10.0;  // m added at mu = 1
constexpr double kTextHeight = 3.0;      // m above the sensor

visualization_msgs::Marker weak_direction_arrow(const DegenerationState& msg) {
  const double mu = std::clamp(msg.mu, 0.0, 1.0);
  std::optional<Eigen::Vector3d> head;
  if (msg.valid) {
    head = (kArrowMinLength + kArrowMuLength * mu) *
           Eigen::Vector3d(msg.weak_direction.x, msg.weak_direction.y, msg.weak_direction.z);
  }
  return arrow_marker(msg.header, "weak_direction", head,
                      {0.5, 1.0, 1.5, static_cast<float>(mu), static_cast<float>(1.0 - mu), 0.1f});
}

visualization_msgs::Marker mu_text(const DegenerationState& msg) {
  char line[96];
  if (msg.valid) {
    std::snprintf(line, sizeof(line), "mu %.2f  beta0 %.1f deg", msg.mu, msg.beta0_deg);
  } else {
    std::snprintf(line, sizeof(line), "mu unknown  beta0 %.1f deg", msg.beta0_deg);
  }
  return text_marker(msg.header, "degeneration", 1, line, kTextHeight, 2.0);
}

}  // namespace

DegenerationState degeneration_to_ros(const AmbientFilterResult& filtered,
                                      const std_msgs::Header& header) {
  DegenerationState msg;
  msg.header = header;
  const Degeneration& degeneration = filtered.degeneration;
  msg.valid = degeneration.valid;
  msg.mu = filtered.mu;
  msg.mu_raw = degeneration.mu;
  msg.beta0_deg = static_cast<float>(filtered.beta0_deg);
  msg.weak_direction.x = degeneration.weak_direction.x();
  msg.weak_direction.y = degeneration.weak_direction.y();
  msg.weak_direction.z = 0.0;
  msg.skeleton_points = static_cast<uint32_t>(std::max(filtered.skeleton_points, 0));
  msg.normals = static_cast<uint32_t>(std::max(degeneration.normals, 0));
  return msg;
}

namespace {

Degeneration degeneration_from_ros(const DegenerationState& msg) {
  Degeneration degeneration;
  degeneration.valid = msg.valid;
  degeneration.mu = msg.mu_raw;
  degeneration.weak_direction = Eigen::Vector2d(msg.weak_direction.x, msg.weak_direction.y);
  degeneration.normals = static_cast<int>(msg.normals);
  return degeneration;
}

}  // namespace

std::optional<WeakDirectionPrior> weak_direction_prior_from_ros(const MappingParams& params,
                                                                const DegenerationState& msg) {
  return weak_direction_prior(params, degeneration_from_ros(msg), msg.mu);
}

std::optional<SceneDegeneration> scene_degeneration_from_ros(const DegenerationState& msg) {
  return scene_degeneration(degeneration_from_ros(msg), msg.mu);
}

visualization_msgs::MarkerArray degeneration_markers(const DegenerationState& msg) {
  visualization_msgs::MarkerArray markers;
  markers.markers = {weak_direction_arrow(msg), mu_text(msg)};
  return markers;
}

}  // namespace adaptive_lego_loam::ros_bridge
