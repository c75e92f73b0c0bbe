#pragma once
// What the stages tell each other about the motion sensors, as messages: the prediction's priors
// of a scan (adaptive_lego_loam/MotionPriors, feature_association -> map_optimization), what
// scan-to-map saw of it (adaptive_lego_loam/MapMatch, back to feature_association's
// MotionSensors::update), and rviz's arrow along the IMU's gravity.

#include <adaptive_lego_loam/MapMatch.h>
#include <adaptive_lego_loam/MotionPriors.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "adaptive_lego_loam/core/mapping/scan_to_map.h"
#include "adaptive_lego_loam/core/motion_sensors/motion_prediction.h"

namespace adaptive_lego_loam::ros_bridge {

// The motion and gravity priors of `prediction` (the sweep is not sent: only the odometry
// de-skews); nullptr or an empty prediction gives both flags false.
MotionPriors motion_priors_to_ros(const MotionPrediction* prediction,
                                  const std_msgs::Header& header);
// The priors back, as LidarMapping::process takes them (no sweep). Throws IoError naming `source`
// on a non-finite number or a zero quaternion.
MotionPrediction motion_priors_from_ros(const MotionPriors& msg, const std::string& source);

// What feature_association learns of a mapped scan: the mapped motion since the previous scan
// (the odometry's motion model) and what MotionSensors::update takes.
struct MappingFeedback {
  std::optional<Eigen::Isometry3d> motion;  // MappingOutput::motion (none on the first scan)
  bool matched = false;
  Matrix6d information = Matrix6d::Zero();  // MapMatchResult::information
  bool motion_prior = false;                // MapMatchResult::motion_prior
  // MotionSensors::update's motion: only of a matched scan, as the offline pipeline hands it.
  std::optional<Eigen::Isometry3d> matched_motion() const {
    return matched ? motion : std::nullopt;
  }
};

// `match` and the mapped motion since the previous scan (MappingOutput's), when known.
MapMatch map_match_to_ros(const MapMatchResult& match,
                          const std::optional<Eigen::Isometry3d>& motion,
                          const std_msgs::Header& header);
// Throws IoError naming `source` on a non-finite number or a zero quaternion.
MappingFeedback mapping_feedback_from_ros(const MapMatch& msg, const std::string& source);

// An arrow from the sensor along gravity's up direction (the message's frame), 5 m long; deleted
// when the priors have no gravity.
visualization_msgs::Marker gravity_marker(const MotionPriors& msg);

}  // namespace adaptive_lego_loam::ros_bridge
