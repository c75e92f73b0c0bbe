#pragma once
// rviz markers of how well the mapped pose is known: a bar through the sensor along the
// translation's least-known direction, 3 sigma to either side (at most kMaxBarHalfLength m), and
// that 3 sigma as text above it. Green while the LiDAR fixes every direction, orange while a
// degenerate direction is held by the motion sensors' prior, red while nothing holds it.

#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Core>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"

namespace adaptive_lego_loam::ros_bridge {

constexpr double kMaxBarHalfLength = 30.0;  // m

// `covariance`: the published one (the core's convention, sensor frame); `lidar`: what the
// LiDAR's correspondences fix worst, and whether a prior holds it.
visualization_msgs::MarkerArray uncertainty_markers(const std_msgs::Header& header,
                                                    const Matrix6d& covariance,
                                                    const WeakestDirection& lidar);

}  // namespace adaptive_lego_loam::ros_bridge
