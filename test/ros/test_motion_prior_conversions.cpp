// The motion sensors' priors and the mapping's feedback as messages between the stages, and the
// gravity arrow.

#include <gtest/gtest.h>

#include <limits>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/motion_prior_conversions.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::ros_bridge;

namespace {

std_msgs::Header scan_header() {
  std_msgs::Header header;
  header.frame_id = "velodyne";
  header.stamp.fromSec(1e9 + 0.3);
  return header;
}

Eigen::Isometry3d a_motion() {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = rotation_exp(Eigen::Vector3d(0.01, -0.02, 0.05));
  motion.translation() = Eigen::Vector3d(0.8, 0.05, -0.01);
  return motion;
}

Matrix6d an_information() {
  Matrix6d information;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c)
      information(r, c) = 1.0 / (1.0 + r + c) + (r == c ? 1e4 * (r + 1) : 0.0);
  }
  return information;
}

MotionPrediction a_prediction() {
  MotionPrediction prediction;
  prediction.motion = MotionPrior{a_motion(), an_information(), true, false};
  GravityPrior gravity;
  gravity.up = Eigen::Vector3d(0.05, -0.02, 1.0).normalized();
  gravity.covariance = Eigen::Matrix3d::Identity() * 1e-4;
  gravity.covariance(0, 1) = gravity.covariance(1, 0) = 2e-5;
  prediction.gravity = gravity;
  prediction.sweep = SweepMotion{{Eigen::Isometry3d::Identity()}};
  return prediction;
}

const MotionPrediction kPrediction = a_prediction();

}  // namespace

TEST(MotionPriorConversions, ThePriorsGoThroughAMessage) {
  const MotionPriors msg = motion_priors_to_ros(&kPrediction, scan_header());
  EXPECT_EQ(msg.header.frame_id, "velodyne");
  EXPECT_TRUE(msg.has_motion);
  EXPECT_TRUE(msg.has_gravity);
  const MotionPrediction back = motion_priors_from_ros(msg, "motion_priors");
  ASSERT_TRUE(back.motion);
  // Exact, to the bit: a quaternion's round trip would move the graph's poses off run_sequence's.
  EXPECT_EQ(back.motion->motion.matrix(), a_motion().matrix());
  EXPECT_EQ(back.motion->information, an_information());  // row-major, exact
  EXPECT_TRUE(back.motion->from_imu);
  EXPECT_FALSE(back.motion->from_wheel);
  ASSERT_TRUE(back.gravity);
  EXPECT_EQ(back.gravity->up, a_prediction().gravity->up);
  EXPECT_EQ(back.gravity->covariance, a_prediction().gravity->covariance);
  EXPECT_FALSE(back.sweep) << "the sweep is the odometry's alone";
}

TEST(MotionPriorConversions, NoPredictionIsAnEmptyOne) {
  const MotionPriors msg = motion_priors_to_ros(nullptr, scan_header());
  EXPECT_FALSE(msg.has_motion);
  EXPECT_FALSE(msg.has_gravity);
  EXPECT_TRUE(motion_priors_from_ros(msg, "motion_priors").empty());
  MotionPrediction gravity_only = a_prediction();
  gravity_only.motion.reset();
  const MotionPrediction back =
      motion_priors_from_ros(motion_priors_to_ros(&gravity_only, scan_header()), "t");
  EXPECT_FALSE(back.motion);
  EXPECT_TRUE(back.gravity);
}

TEST(MotionPriorConversions, ANonFiniteInformationIsAnErrorNamingTheTopic) {
  MotionPriors msg = motion_priors_to_ros(&kPrediction, scan_header());
  msg.motion_information[7] = std::numeric_limits<double>::quiet_NaN();
  try {
    motion_priors_from_ros(msg, "/motion_priors");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/motion_priors: motion_information"), std::string::npos)
        << e.what();
  }
  msg = motion_priors_to_ros(&kPrediction, scan_header());
  msg.up.x = msg.up.y = msg.up.z = 0.0;
  EXPECT_THROW(motion_priors_from_ros(msg, "/motion_priors"), IoError);
  msg = motion_priors_to_ros(&kPrediction, scan_header());
  msg.motion[0] = 2.0;  // not a rotation
  EXPECT_THROW(motion_priors_from_ros(msg, "/motion_priors"), IoError);
}

TEST(MotionPriorConversions, TheMappingsFeedbackTeachesTheSensorsOnlyWhenMatched) {
  MapMatchResult match;
  match.matched = true;
  match.information = an_information();
  match.degenerate_directions = 2;
  match.motion_prior = true;
  const MapMatch msg = map_match_to_ros(match, a_motion(), scan_header());
  EXPECT_EQ(msg.degenerate_directions, 2);
  const MappingFeedback feedback = mapping_feedback_from_ros(msg, "map_match");
  // Whether the prior held a direction: the wheel's scale learns only from scans it did not.
  EXPECT_TRUE(feedback.motion_prior);
  ASSERT_TRUE(feedback.matched_motion());
  EXPECT_EQ(feedback.matched_motion()->matrix(), a_motion().matrix());
  EXPECT_EQ(feedback.information, an_information());

  // The pose is the guess: nothing to learn from, but the odometry still takes the motion.
  match.matched = false;
  const MappingFeedback unmatched =
      mapping_feedback_from_ros(map_match_to_ros(match, a_motion(), scan_header()), "m");
  EXPECT_FALSE(unmatched.matched_motion());
  ASSERT_TRUE(unmatched.motion);
  EXPECT_TRUE(unmatched.motion->isApprox(a_motion(), 1e-12));
  match.matched = true;  // the first scan: no motion yet
  const MapMatch first = map_match_to_ros(match, std::nullopt, scan_header());
  EXPECT_FALSE(first.has_motion);
  EXPECT_FALSE(mapping_feedback_from_ros(first, "m").motion);
}

TEST(MotionPriorConversions, TheGravityArrowPointsUpFromTheSensor) {
  const MotionPriors msg = motion_priors_to_ros(&kPrediction, scan_header());
  const visualization_msgs::Marker arrow = gravity_marker(msg);
  EXPECT_EQ(arrow.header.frame_id, "velodyne");
  EXPECT_EQ(arrow.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(arrow.type, visualization_msgs::Marker::ARROW);
  ASSERT_EQ(arrow.points.size(), 2u);
  EXPECT_EQ(arrow.points[0].z, 0.0);
  const Eigen::Vector3d head(arrow.points[1].x, arrow.points[1].y, arrow.points[1].z);
  EXPECT_NEAR(head.norm(), 5.0, 1e-9);
  EXPECT_GT(head.normalized().dot(a_prediction().gravity->up), 1.0 - 1e-12);
  EXPECT_EQ(gravity_marker(motion_priors_to_ros(nullptr, scan_header())).action,
            visualization_msgs::Marker::DELETE);
}
