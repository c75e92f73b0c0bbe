#pragma once
// The ambient filter's degeneration estimate as adaptive_lego_loam/DegenerationState, the
// mapping prior it implies, and rviz markers for it.

#include <adaptive_lego_loam/DegenerationState.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <optional>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/mapping/scan_to_map.h"

namespace adaptive_lego_loam::ros_bridge {

DegenerationState degeneration_to_ros(const AmbientFilterResult& filtered,
                                      const std_msgs::Header& header);

// map_optimization's weak-direction prior from the message: the core's weak_direction_prior on
// the fields the message carries (none when the prior is off or mu unknown).
std::optional<WeakDirectionPrior> weak_direction_prior_from_ros(const MappingParams& params,
                                                                const DegenerationState& msg);
// The scene's weak direction and mu the mapping's motion-sensor priors weigh (none: mu unknown).
std::optional<SceneDegeneration> scene_degeneration_from_ros(const DegenerationState& msg);

// In the message's frame: an arrow from the sensor along the weak direction, longer and redder
// as mu grows (deleted when mu is unknown), and a text with mu and beta0 above the sensor.
visualization_msgs::MarkerArray degeneration_markers(const DegenerationState& msg);

}  // namespace adaptive_lego_loam::ros_bridge
