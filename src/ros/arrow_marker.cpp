#include "adaptive_lego_loam/ros/arrow_marker.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

geometry_msgs::Point point_of(const Eigen::Vector3d& p) {
  geometry_msgs::Point out;
  out.x = p.x();
  out.y = p.y();
  out.z = p.z();
  return out;
}

// A marker of `type` from `from` to `to` (id 0 in `ns`) in `style`'s colour, or its DELETE.
visualization_msgs::Marker two_point_marker(const std_msgs::Header& header, const std::string& ns,
                                            int type, const std::optional<Eigen::Vector3d>& from,
                                            const std::optional<Eigen::Vector3d>& to,
                                            const ArrowStyle& style) {
  visualization_msgs::Marker marker;
  marker.header = header;
  marker.ns = ns;
  marker.id = 0;
  marker.type = type;
  if (!from || !to) {
    marker.action = visualization_msgs::Marker::DELETE;
    return marker;
  }
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.points = {point_of(*from), point_of(*to)};
  marker.color.r = style.red;
  marker.color.g = style.green;
  marker.color.b = style.blue;
  marker.color.a = 1.0f;
  return marker;
}

}  // namespace

visualization_msgs::Marker arrow_marker(const std_msgs::Header& header, const std::string& ns,
                                        const std::optional<Eigen::Vector3d>& head,
                                        const ArrowStyle& style) {
  visualization_msgs::Marker arrow = two_point_marker(header, ns, visualization_msgs::Marker::ARROW,
                                                      Eigen::Vector3d::Zero().eval(), head, style);
  arrow.scale.x = style.shaft_diameter;
  arrow.scale.y = style.head_diameter;
  arrow.scale.z = style.head_length;
  return arrow;
}

visualization_msgs::Marker bar_marker(const std_msgs::Header& header, const std::string& ns,
                                      const std::optional<Eigen::Vector3d>& half, double width,
                                      const ArrowStyle& color) {
  const std::optional<Eigen::Vector3d> from =
      half ? std::optional<Eigen::Vector3d>(-*half) : std::nullopt;
  visualization_msgs::Marker bar =
      two_point_marker(header, ns, visualization_msgs::Marker::LINE_LIST, from, half, color);
  bar.scale.x = width;
  return bar;
}

visualization_msgs::Marker text_marker(const std_msgs::Header& header, const std::string& ns,
                                       int id, const std::string& text, double height,
                                       double letter_height) {
  visualization_msgs::Marker marker;
  marker.header = header;
  marker.ns = ns;
  marker.id = id;
  marker.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.pose.position.z = height;
  marker.scale.z = letter_height;
  marker.color.r = marker.color.g = marker.color.b = marker.color.a = 1.0f;
  marker.text = text;
  return marker;
}

}  // namespace adaptive_lego_loam::ros_bridge
