#include "adaptive_lego_loam/ros/uncertainty_markers.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/ros/arrow_marker.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

constexpr double kBarWidth = 0.3;    // m
constexpr double kTextHeight = 8.0;  // m above the sensor, over the degeneration's text

ArrowStyle colour_of(const WeakestDirection& lidar) {
  ArrowStyle colour;
  colour.blue = 0.1f;
  if (!lidar.degenerate) {
    colour.red = 0.2f;  // green
  } else if (lidar.held) {
    colour.green = 0.6f;  // orange
  } else {
    colour.green = 0.1f;  // red
  }
  return colour;
}

}  // namespace

visualization_msgs::MarkerArray uncertainty_markers(const std_msgs::Header& header,
                                                    const Matrix6d& covariance,
                                                    const WeakestDirection& lidar) {
  const Eigen::Matrix3d translation = covariance.bottomRightCorner<3, 3>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(
      0.5 * (translation + translation.transpose()));
  const double sigma = std::sqrt(std::max(solver.eigenvalues()(2), 0.0));
  const Eigen::Vector3d direction = solver.eigenvectors().col(2);
  const double half_length = std::min(3.0 * sigma, kMaxBarHalfLength);
  char line[96];
  if (sigma * sigma >= 0.999 * kUnknownVariance) {
    std::snprintf(line, sizeof(line), "pose unknown along the bar");
  } else {
    std::snprintf(line, sizeof(line), "pose 3 sigma %.2f m", 3.0 * sigma);
  }
  visualization_msgs::MarkerArray markers;
  markers.markers = {
      bar_marker(header, "pose_uncertainty", Eigen::Vector3d(half_length * direction), kBarWidth,
                 colour_of(lidar)),
      text_marker(header, "pose_uncertainty", 1, line, kTextHeight, 1.5)};
  return markers;
}

}  // namespace adaptive_lego_loam::ros_bridge
