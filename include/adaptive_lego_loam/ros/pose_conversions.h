#pragma once
// Poses as ROS messages: nav_msgs/Odometry, TF transforms, nav_msgs/Path. A pose is the child
// frame's pose in the parent frame (x_parent = pose * x_child), as everywhere in the core.

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/time.h>
#include <std_msgs/Header.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace adaptive_lego_loam::ros_bridge {

// `header.frame_id` is the parent frame; the twist stays zero.
nav_msgs::Odometry odometry_to_ros(const Eigen::Isometry3d& pose, const std_msgs::Header& header,
                                   const std::string& child_frame);

// A covariance of `pose` over right perturbations ([rotation vector, translation] in the child
// frame, the core's) as nav_msgs/Odometry's pose covariance: [x, y, z, rotation about x, y, z]
// in the parent frame's axes, row-major.
void set_pose_covariance(const Eigen::Matrix<double, 6, 6>& covariance,
                         geometry_msgs::PoseWithCovariance& pose);
// set_pose_covariance read back: the core's covariance of the message's pose (its orientation
// must be a valid quaternion). Throws IoError naming `source` on a non-finite entry.
Eigen::Matrix<double, 6, 6> pose_covariance_from_ros(const geometry_msgs::PoseWithCovariance& pose,
                                                     const std::string& source);

// Throws IoError naming `source` on a non-finite number or a zero quaternion; the quaternion is
// normalised.
Eigen::Isometry3d pose_from_ros(const geometry_msgs::Pose& pose, const std::string& source);

// A motion over `dt` seconds (the child frame's pose at the end in its pose at the start) as the
// constant velocity nav_msgs/Odometry's twist holds, in the child frame: translation / dt and
// rotation vector / dt; and back. dt > 0.
geometry_msgs::Twist motion_to_twist(const Eigen::Isometry3d& motion, double dt);
// Throws IoError naming `source` on a non-finite number.
Eigen::Isometry3d motion_from_twist(const geometry_msgs::Twist& twist, double dt,
                                    const std::string& source);
// aft_mapped_to_init says whether its twist holds the mapped motion (there is none on the first
// scan after a start) in the first element of the twist covariance, -1 meaning "no estimate" as
// in sensor_msgs.
void mark_no_mapped_motion(nav_msgs::Odometry& msg);
bool has_mapped_motion(const nav_msgs::Odometry& msg);

geometry_msgs::TransformStamped transform_to_ros(const Eigen::Isometry3d& pose,
                                                 const std_msgs::Header& header,
                                                 const std::string& child_frame);

// Throws std::invalid_argument when poses and stamps differ in length.
nav_msgs::Path path_to_ros(const std::vector<Eigen::Isometry3d>& poses,
                           const std::vector<ros::Time>& stamps, const std::string& frame);

}  // namespace adaptive_lego_loam::ros_bridge
