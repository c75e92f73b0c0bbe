#pragma once
// An rviz arrow from a frame's origin: the degeneration's weak direction, the IMU's gravity.

#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>

#include <Eigen/Core>
#include <optional>
#include <string>

namespace adaptive_lego_loam::ros_bridge {

struct ArrowStyle {
  double shaft_diameter = 0.5;  // m
  double head_diameter = 1.0;   // m
  double head_length = 1.5;     // m
  float red = 1.0f, green = 1.0f, blue = 1.0f;
};

// An arrow from the origin of `header`'s frame to `head` (id 0 in `ns`), or the DELETE of that
// arrow when there is nothing to show.
visualization_msgs::Marker arrow_marker(const std_msgs::Header& header, const std::string& ns,
                                        const std::optional<Eigen::Vector3d>& head,
                                        const ArrowStyle& style);

}  // namespace adaptive_lego_loam::ros_bridge
