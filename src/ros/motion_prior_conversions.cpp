#include "adaptive_lego_loam/ros/motion_prior_conversions.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/arrow_marker.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

constexpr double kGravityArrowLength = 5.0;  // m: above the degeneration markers' text

template <int N, std::size_t Size>
void set_matrix(boost::array<double, Size>& out, const Eigen::Matrix<double, N, N>& m) {
  static_assert(Size == N * N);
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c < N; ++c)
      out[r * N + c] = m(r, c);
  }
}

template <int N, std::size_t Size>
Eigen::Matrix<double, N, N> matrix_of(const boost::array<double, Size>& in,
                                      const std::string& source, const char* field) {
  static_assert(Size == N * N);
  Eigen::Matrix<double, N, N> m;
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c < N; ++c)
      m(r, c) = in[r * N + c];
  }
  if (!m.allFinite()) throw IoError(source + ": " + field + " holds a non-finite number");
  return m;
}

void set_pose(boost::array<double, 12>& out, const Eigen::Isometry3d& pose) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c)
      out[r * 4 + c] = pose.matrix()(r, c);
  }
}

Eigen::Isometry3d pose_of(const boost::array<double, 12>& in, const std::string& source) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c)
      pose.matrix()(r, c) = in[r * 4 + c];
  }
  const Eigen::Matrix3d rotation = pose.linear();
  if (!pose.matrix().allFinite() ||
      !(rotation.transpose() * rotation).isApprox(Eigen::Matrix3d::Identity(), 1e-6)) {
    throw IoError(source + ": motion is not a rigid motion ([R | t], R a rotation)");
  }
  return pose;
}

}  // namespace

MotionPriors motion_priors_to_ros(const MotionPrediction* prediction,
                                  const std_msgs::Header& header) {
  MotionPriors msg;
  msg.header = header;
  set_pose(msg.motion, Eigen::Isometry3d::Identity());
  msg.up.z = 1.0;
  if (prediction && prediction->motion) {
    msg.has_motion = true;
    set_pose(msg.motion, prediction->motion->motion);
    set_matrix(msg.motion_information, prediction->motion->information);
    msg.motion_from_imu = prediction->motion->from_imu;
    msg.motion_from_wheel = prediction->motion->from_wheel;
  }
  if (prediction && prediction->gravity) {
    msg.has_gravity = true;
    tf2::toMsg(prediction->gravity->up, msg.up);
    set_matrix(msg.up_covariance, prediction->gravity->covariance);
  }
  return msg;
}

MotionPrediction motion_priors_from_ros(const MotionPriors& msg, const std::string& source) {
  MotionPrediction prediction;
  if (msg.has_motion) {
    MotionPrior prior;
    prior.motion = pose_of(msg.motion, source);
    prior.information = matrix_of<6>(msg.motion_information, source, "motion_information");
    prior.from_imu = msg.motion_from_imu;
    prior.from_wheel = msg.motion_from_wheel;
    prediction.motion = prior;
  }
  if (msg.has_gravity) {
    GravityPrior gravity;
    gravity.up = Eigen::Vector3d(msg.up.x, msg.up.y, msg.up.z);
    if (!gravity.up.allFinite() || gravity.up.norm() < 0.5) {
      throw IoError(source + ": up is not a unit vector");
    }
    gravity.covariance = matrix_of<3>(msg.up_covariance, source, "up_covariance");
    prediction.gravity = gravity;
  }
  return prediction;
}

MapMatch map_match_to_ros(const MapMatchResult& match,
                          const std::optional<Eigen::Isometry3d>& motion,
                          const std_msgs::Header& header) {
  MapMatch msg;
  msg.header = header;
  msg.matched = match.matched;
  set_pose(msg.motion, Eigen::Isometry3d::Identity());
  if (motion) {
    msg.has_motion = true;
    set_pose(msg.motion, *motion);
  }
  set_matrix(msg.information, match.information);
  msg.degenerate_directions = match.degenerate_directions;
  msg.motion_prior = match.motion_prior;
  return msg;
}

MappingFeedback mapping_feedback_from_ros(const MapMatch& msg, const std::string& source) {
  MappingFeedback feedback;
  feedback.matched = msg.matched;
  feedback.motion_prior = msg.motion_prior;
  feedback.information = matrix_of<6>(msg.information, source, "information");
  if (msg.has_motion) feedback.motion = pose_of(msg.motion, source);
  return feedback;
}

visualization_msgs::Marker gravity_marker(const MotionPriors& msg) {
  std::optional<Eigen::Vector3d> head;
  if (msg.has_gravity) head = kGravityArrowLength * Eigen::Vector3d(msg.up.x, msg.up.y, msg.up.z);
  return arrow_marker(msg.header, "gravity", head, {0.3, 0.7, 1.0, 0.2f, 0.6f, 1.0f});
}

}  // namespace adaptive_lego_loam::ros_bridge
