#include "adaptive_lego_loam/ros/arrow_marker.h"

namespace adaptive_lego_loam::ros_bridge {

visualization_msgs::Marker arrow_marker(const std_msgs::Header& header, const std::string& ns,
                                        const std::optional<Eigen::Vector3d>& head,
                                        const ArrowStyle& style) {
  visualization_msgs::Marker arrow;
  arrow.header = header;
  arrow.ns = ns;
  arrow.id = 0;
  arrow.type = visualization_msgs::Marker::ARROW;
  if (!head) {
    arrow.action = visualization_msgs::Marker::DELETE;
    return arrow;
  }
  arrow.action = visualization_msgs::Marker::ADD;
  arrow.pose.orientation.w = 1.0;
  geometry_msgs::Point tail, tip;
  tip.x = head->x();
  tip.y = head->y();
  tip.z = head->z();
  arrow.points = {tail, tip};
  arrow.scale.x = style.shaft_diameter;
  arrow.scale.y = style.head_diameter;
  arrow.scale.z = style.head_length;
  arrow.color.r = style.red;
  arrow.color.g = style.green;
  arrow.color.b = style.blue;
  arrow.color.a = 1.0f;
  return arrow;
}

visualization_msgs::Marker bar_marker(const std_msgs::Header& header, const std::string& ns,
                                      const std::optional<Eigen::Vector3d>& half, double width,
                                      const ArrowStyle& color) {
  visualization_msgs::Marker bar;
  bar.header = header;
  bar.ns = ns;
  bar.id = 0;
  bar.type = visualization_msgs::Marker::LINE_LIST;
  if (!half) {
    bar.action = visualization_msgs::Marker::DELETE;
    return bar;
  }
  bar.action = visualization_msgs::Marker::ADD;
  bar.pose.orientation.w = 1.0;
  geometry_msgs::Point from, to;
  from.x = -half->x();
  from.y = -half->y();
  from.z = -half->z();
  to.x = half->x();
  to.y = half->y();
  to.z = half->z();
  bar.points = {from, to};
  bar.scale.x = width;
  bar.color.r = color.red;
  bar.color.g = color.green;
  bar.color.b = color.blue;
  bar.color.a = 1.0f;
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
