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

}  // namespace adaptive_lego_loam::ros_bridge
