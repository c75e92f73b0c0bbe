#pragma once
// rviz markers about a frame's origin: arrows (the degeneration's weak direction, the IMU's
// gravity), a bar through it (the pose's least-known direction) and a line of text above it.

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

// A bar from -half to +half through the origin of `header`'s frame (id 0 in `ns`), `width` m
// thick, or the DELETE of that bar.
visualization_msgs::Marker bar_marker(const std_msgs::Header& header, const std::string& ns,
                                      const std::optional<Eigen::Vector3d>& half, double width,
                                      const ArrowStyle& color);

// White text facing the camera, `height` m above the origin of `header`'s frame, letters
// `letter_height` m high (id `id` in `ns`).
visualization_msgs::Marker text_marker(const std_msgs::Header& header, const std::string& ns,
                                       int id, const std::string& text, double height,
                                       double letter_height);

}  // namespace adaptive_lego_loam::ros_bridge
