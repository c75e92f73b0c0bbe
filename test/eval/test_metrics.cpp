#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/core/common/rotations.h"
#include "adaptive_lego_loam/eval/metrics.h"
#include "adaptive_lego_loam/io/pose_files.h"

using namespace adaptive_lego_loam;
using Poses = std::vector<Eigen::Isometry3d>;

namespace {

const std::string kSeq07 = std::string(TEST_DATA_DIR) + "/kitti_seq07";

Eigen::Isometry3d motion(double forward_m, double yaw_deg = 0, double left_m = 0) {
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  step.linear() =
      Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  step.translation() << forward_m, left_m, 0;
  return step;
}

// First pose identity, then each pose is the previous one moved by steps[i].
Poses integrate(const Poses& steps) {
  Poses poses{Eigen::Isometry3d::Identity()};
  for (const Eigen::Isometry3d& step : steps)
    poses.push_back(poses.back() * step);
  return poses;
}

Poses repeated(const Eigen::Isometry3d& step, int count) {
  return Poses(count, step);
}

// A 3D path that turns, climbs and rolls, ~1200 m long.
Poses winding_trajectory() {
  Poses steps;
  for (int i = 0; i < 1200; ++i) {
    Eigen::Isometry3d step = motion(1.0, 0.4 * std::sin(i / 40.0));
    step.linear() =
        step.linear() *
        Eigen::AngleAxisd(0.002 * std::cos(i / 25.0), Eigen::Vector3d::UnitY()).toRotationMatrix();
    steps.push_back(step);
  }
  return integrate(steps);
}

Poses transformed(const Eigen::Isometry3d& transform, const Poses& poses) {
  Poses result;
  for (const Eigen::Isometry3d& pose : poses)
    result.push_back(transform * pose);
  return result;
}

}  // namespace

TEST(Metrics, IdenticalTrajectoriesGiveZeroEverywhere) {
  const Poses truth = winding_trajectory();
  const OdometryEvaluation evaluation = evaluate_odometry(truth, truth);
  EXPECT_EQ(evaluation.frames_used, truth.size());
  EXPECT_GT(evaluation.kitti.segments, 0);
  EXPECT_NEAR(*evaluation.kitti.translation_percent, 0, 1e-9);
  EXPECT_NEAR(*evaluation.kitti.rotation_deg_per_100m, 0, 1e-9);
  EXPECT_NEAR(*evaluation.rpe.translation_rmse_m, 0, 1e-12);
  EXPECT_NEAR(*evaluation.rpe.rotation_rmse_deg, 0, 1e-9);
  EXPECT_NEAR(evaluation.ate.rmse_m, 0, 1e-9);
}

TEST(Metrics, OnePercentLongerStepsGiveOnePercent) {
  const double step_m = 0.5;
  const Poses truth = integrate(repeated(motion(step_m), 2000));  // 1000 m straight
  const Poses estimate = integrate(repeated(motion(1.01 * step_m), 2000));
  const KittiSegmentError kitti = kitti_segment_error(estimate, truth);
  EXPECT_DOUBLE_EQ(kitti.ground_truth_path_m, 1000.0);
  EXPECT_NEAR(*kitti.translation_percent, 1.0, 1e-9);
  EXPECT_NEAR(*kitti.rotation_deg_per_100m, 0.0, 1e-12);
  const RelativePoseError rpe = relative_pose_error(estimate, truth);
  ASSERT_EQ(rpe.translation_m.size(), 2000u);
  EXPECT_NEAR(*rpe.translation_rmse_m, 0.01 * step_m, 1e-12);
  EXPECT_NEAR(*rpe.rotation_rmse_deg, 0.0, 1e-12);
}

TEST(Metrics, SegmentsStartEveryTenthFrameAndNeedTheirFullLength) {
  // 1 m steps over 1000 m: a segment of L m fits from frame s when s + L <= 1000, s = 0, 10, ...
  const Poses truth = integrate(repeated(motion(1.0), 1000));
  const KittiSegmentError kitti = kitti_segment_error(truth, truth);
  ASSERT_EQ(kitti.per_length.size(), 8u);
  int total = 0;
  for (const SegmentLengthError& length : kitti.per_length) {
    EXPECT_EQ(length.segments, static_cast<int>(1000 - length.length_m) / 10 + 1)
        << length.length_m << " m";
    total += length.segments;
  }
  EXPECT_EQ(kitti.segments, 448);
  EXPECT_EQ(total, 448);
}

TEST(Metrics, ConstantYawBiasGivesItsRateInDegPer100m) {
  // Every 1 m step turns by an extra 0.01 deg: 1 deg per 100 m along every segment.
  const Poses truth = integrate(repeated(motion(1.0), 1000));
  const Poses estimate = integrate(repeated(motion(1.0, 0.01), 1000));
  const OdometryEvaluation evaluation = evaluate_odometry(estimate, truth);
  EXPECT_NEAR(*evaluation.kitti.rotation_deg_per_100m, 1.0, 1e-9);
  for (const SegmentLengthError& length : evaluation.kitti.per_length)
    EXPECT_NEAR(length.rotation_deg_per_100m, 1.0, 1e-9) << length.length_m << " m";
  // Each step's translation is right in its own frame; only its heading is off.
  EXPECT_NEAR(*evaluation.rpe.translation_rmse_m, 0.0, 1e-12);
  EXPECT_NEAR(*evaluation.rpe.rotation_rmse_deg, 0.01, 1e-9);
  EXPECT_GT(*evaluation.kitti.translation_percent, 0.1);  // the heading error bends the path
}

TEST(Metrics, RpeLocatesOneBadStep) {
  Poses true_steps = repeated(motion(1.0, 2.0), 10);
  Poses estimated_steps = true_steps;
  estimated_steps[6] = motion(1.0, 2.0, 0.2);  // 0.2 m sideways on the step from frame 6 to 7
  const RelativePoseError rpe =
      relative_pose_error(integrate(estimated_steps), integrate(true_steps));
  ASSERT_EQ(rpe.translation_m.size(), 10u);
  for (std::size_t i = 0; i < 10; ++i)
    EXPECT_NEAR(rpe.translation_m[i], i == 6 ? 0.2 : 0.0, 1e-12) << "pair " << i;
  EXPECT_NEAR(*rpe.translation_rmse_m, 0.2 / std::sqrt(10.0), 1e-12);
}

TEST(Metrics, ShortTrajectoryHasNoKittiSegments) {
  const Poses truth = integrate(repeated(motion(1.0), 99));  // 99 m
  const KittiSegmentError kitti = kitti_segment_error(truth, truth);
  EXPECT_EQ(kitti.segments, 0);
  EXPECT_FALSE(kitti.translation_percent.has_value());
  EXPECT_FALSE(kitti.rotation_deg_per_100m.has_value());
  EXPECT_TRUE(kitti.per_length.empty());
  EXPECT_DOUBLE_EQ(kitti.ground_truth_path_m, 99.0);
  const Poses one_frame{Eigen::Isometry3d::Identity()};
  EXPECT_FALSE(relative_pose_error(one_frame, one_frame).translation_rmse_m.has_value());
}

TEST(Metrics, AteAlignmentRecoversARigidMotion) {
  const Poses truth = winding_trajectory();
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.linear() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  offset.translation() << 12, -40, 3;
  const AbsoluteTrajectoryError ate = absolute_trajectory_error(transformed(offset, truth), truth);
  EXPECT_NEAR(ate.rmse_m, 0, 1e-9);
  EXPECT_TRUE(ate.alignment.isApprox(offset.inverse(), 1e-9));
}

TEST(Metrics, AteOfAnOffsetAlignmentCannotRemove) {
  // Points on a circle in z = 0; the estimate alternates +-0.3 m in z. The offsets have zero mean
  // and no correlation with x or y, so the best rigid alignment is the identity and ATE = 0.3 m.
  Poses truth, estimate;
  for (int k = 0; k < 64; ++k) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() << 20 * std::cos(2 * M_PI * k / 64), 20 * std::sin(2 * M_PI * k / 64), 0;
    truth.push_back(pose);
    pose.translation().z() = k % 2 ? -0.3 : 0.3;
    estimate.push_back(pose);
  }
  const AbsoluteTrajectoryError ate = absolute_trajectory_error(estimate, truth);
  EXPECT_NEAR(ate.rmse_m, 0.3, 1e-9);
  EXPECT_TRUE(ate.alignment.isApprox(Eigen::Isometry3d::Identity(), 1e-9));

  // A constant offset, on the other hand, is what the alignment removes.
  const Poses shifted = transformed(Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.3)), truth);
  EXPECT_NEAR(absolute_trajectory_error(shifted, truth).rmse_m, 0, 1e-9);
}

TEST(Metrics, KittiSeq07CameraPosesToLidarPoses) {
  const Poses camera = read_kitti_poses(kSeq07 + "/poses.txt");
  const Eigen::Isometry3d velo_to_cam = read_kitti_calib_tr(kSeq07 + "/calib.txt");
  const Poses lidar = camera_to_lidar_poses(camera, velo_to_cam);
  ASSERT_EQ(lidar.size(), 5u);
  EXPECT_TRUE(lidar[0].isApprox(Eigen::Isometry3d::Identity(), 1e-9));
  // The camera moves 0.0915 m along its z (forward); the lidar's forward axis is x.
  const Eigen::Vector3d first_step = lidar[1].translation();
  EXPECT_NEAR(first_step.x(), 0.0916, 1e-4);
  EXPECT_LT(std::abs(first_step.y()), 0.005);
  EXPECT_LT(std::abs(first_step.z()), 0.005);
  for (std::size_t i = 0; i < 5; ++i) {
    const Eigen::Matrix4d back =
        velo_to_cam.matrix() * lidar[i].matrix() * velo_to_cam.matrix().inverse();
    EXPECT_LT((back - camera[i].matrix()).cwiseAbs().maxCoeff(), 1e-12) << "pose " << i;
  }
  const Poses exact_identity{Eigen::Isometry3d::Identity()};
  const Eigen::Matrix4d first = camera_to_lidar_poses(exact_identity, velo_to_cam)[0].matrix();
  EXPECT_LT((first - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Metrics, ShorterEstimateUsesTheCommonPrefix) {
  const Poses truth = integrate(repeated(motion(1.0, 1.0), 20));
  const Poses estimate(truth.begin(), truth.begin() + 8);
  const OdometryEvaluation evaluation = evaluate_odometry(estimate, truth);
  EXPECT_EQ(evaluation.frames_used, 8u);
  EXPECT_EQ(evaluation.estimate_frames, 8u);
  EXPECT_EQ(evaluation.ground_truth_frames, 21u);
  EXPECT_EQ(evaluation.rpe.translation_m.size(), 7u);
  EXPECT_DOUBLE_EQ(evaluation.kitti.ground_truth_path_m, 7.0);
  EXPECT_THROW(evaluate_odometry({}, truth), std::invalid_argument);
  EXPECT_THROW(relative_pose_error(estimate, truth), std::invalid_argument);
}

TEST(Metrics, AStraightDriveEstimatedTenPercentShortReachesNinetyPercent) {
  const Poses truth = integrate(repeated(motion(1.0), 100));
  const EndDrift drift = end_drift(integrate(repeated(motion(0.9), 100)), truth);
  EXPECT_NEAR(*drift.reach_ratio, 0.9, 1e-12);
  EXPECT_NEAR(*drift.along_track_percent, -10.0, 1e-9);
  EXPECT_NEAR(*drift.cross_track_percent, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(drift.ground_truth_path_m, 100.0);
  EXPECT_NEAR(drift.estimated_path_m, 90.0, 1e-9);
  // Running on past the true end: the true path's last step goes on straight.
  const EndDrift beyond = end_drift(integrate(repeated(motion(1.1), 100)), truth);
  EXPECT_NEAR(*beyond.along_track_percent, 10.0, 1e-9);
  EXPECT_NEAR(*beyond.reach_ratio, 1.1, 1e-12);
}

TEST(Metrics, ASidewaysDriftIsCrossTrack) {
  // Every step 2 cm to the left: the end 2 m off a 100 m path, as far along it as the truth's.
  const Poses truth = integrate(repeated(motion(1.0), 100));
  const EndDrift drift = end_drift(integrate(repeated(motion(1.0, 0, 0.02), 100)), truth);
  EXPECT_NEAR(*drift.cross_track_percent, 2.0, 1e-9);
  EXPECT_NEAR(*drift.along_track_percent, 0.0, 1e-9);
  EXPECT_NEAR(*drift.reach_ratio, std::sqrt(1.0 + 0.02 * 0.02), 1e-12);
}

TEST(Metrics, AlongTrackFollowsACurve) {
  // A quarter circle of 180 m; the estimate stays on it but covers 90 % of it.
  const Poses truth = integrate(repeated(motion(1.0, 0.5), 180));
  const EndDrift short_of = end_drift(integrate(repeated(motion(0.9, 0.45), 180)), truth);
  // (Both polygons' corners lie on circles of the same radius a few centimetres apart.)
  EXPECT_NEAR(*short_of.along_track_percent, -10.0, 0.05);
  EXPECT_NEAR(*short_of.cross_track_percent, 0.0, 0.05);
  EXPECT_NEAR(*short_of.reach_ratio, 0.9, 1e-9);
  // The true end moved 3 m outward, away from the curve's centre: all of it cross-track.
  Poses outside = truth;
  const Eigen::Vector3d outward = -truth.back().linear().col(1);  // right of the heading
  outside.back().translation() += 3.0 * outward;
  const EndDrift off = end_drift(outside, truth);
  EXPECT_NEAR(*off.cross_track_percent, 100.0 * 3.0 / 180.0, 0.05);
  EXPECT_NEAR(*off.along_track_percent, 0.0, 0.05);
  // Standing still there is no path to measure against.
  const Poses standing(5, Eigen::Isometry3d::Identity());
  EXPECT_FALSE(end_drift(standing, standing).reach_ratio.has_value());
  EXPECT_FALSE(end_drift(standing, standing).along_track_percent.has_value());
}

TEST(Metrics, TheConstantVelocityBaselineKeepsTheFirstSecondsMotion) {
  // Turning at a constant rate, the baseline is the truth itself.
  const Poses circling = integrate(repeated(motion(1.5, 2.0, 0.05), 120));
  const Poses same = constant_velocity_baseline(circling, 10);
  ASSERT_EQ(same.size(), circling.size());
  for (std::size_t i = 0; i < circling.size(); ++i)
    EXPECT_TRUE(same[i].isApprox(circling[i], 1e-9)) << i;
  // Speeding up from 10 to 20 m/s on a straight road (0.1 s scans): the baseline keeps the mean
  // speed of the first second, 10.5 m/s, and falls behind.
  Poses steps;
  for (int i = 0; i < 100; ++i)
    steps.push_back(motion(1.0 + 0.01 * i));
  const Poses truth = integrate(steps);
  const Poses baseline = constant_velocity_baseline(truth, 10);
  EXPECT_NEAR(baseline[1].translation().x(), 1.045, 1e-12);
  const EndDrift drift = end_drift(baseline, truth);
  EXPECT_NEAR(*drift.reach_ratio, 104.5 / 149.5, 1e-9);
  EXPECT_NEAR(*drift.cross_track_percent, 0.0, 1e-9);
  // A window longer than the drive takes the whole drive.
  EXPECT_NEAR(constant_velocity_baseline(truth, 1000).back().translation().x(),
              truth.back().translation().x(), 1e-9);
  EXPECT_EQ(constant_velocity_baseline(Poses{Eigen::Isometry3d::Identity()}, 10).size(), 1u);
}

namespace {

// Wheel odometry at 50 Hz reporting `speed` m/s forward and `yaw_rate` rad/s from -0.1 s to `end`.
std::vector<WheelOdometrySample> wheel_samples(double speed, double yaw_rate, double end) {
  std::vector<WheelOdometrySample> samples;
  for (int i = 0; - 0.1 + 0.02 * i <= end + 1e-9; ++i) {
    WheelOdometrySample sample;
    sample.stamp = -0.1 + 0.02 * i;
    sample.linear_velocity.x() = speed;
    sample.angular_velocity.z() = yaw_rate;
    samples.push_back(sample);
  }
  return samples;
}

// The base frame's pose after `t` s at a constant forward speed and yaw rate (an exact arc).
Eigen::Isometry3d arc(double speed, double yaw_rate, double t) {
  const double yaw = yaw_rate * t;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() << speed / yaw_rate * std::sin(yaw), speed / yaw_rate * (1 - std::cos(yaw)), 0;
  return pose;
}

}  // namespace

TEST(Metrics, TheWheelBaselineIsTheOdometryAloneScaleErrorIncluded) {
  // 10 m/s down a straight road, the odometry 2 % long: the baseline overshoots by 2 %.
  std::vector<double> times;
  for (int i = 0; i <= 100; ++i)
    times.push_back(0.1 * i);
  const Poses straight = integrate(repeated(motion(1.0), 100));
  const Poses long_by_2 =
      wheel_baseline(straight, times, wheel_samples(10.2, 0.0, 10.0), WheelOdometryParams{});
  ASSERT_EQ(long_by_2.size(), straight.size());
  EXPECT_NEAR(*end_drift(long_by_2, straight).reach_ratio, 1.02, 1e-9);
  // The samples stop after 5 s: the last motion is kept to the end.
  const Poses coasting =
      wheel_baseline(straight, times, wheel_samples(10.0, 0.0, 5.0), WheelOdometryParams{});
  EXPECT_NEAR(coasting.back().translation().x(), 100.0, 1e-6);
  EXPECT_THROW(
      wheel_baseline(straight, {0.0, 0.1}, wheel_samples(10.0, 0.0, 5.0), WheelOdometryParams{}),
      std::invalid_argument);
}

TEST(Metrics, TheWheelBaselineMovesTheBasesMotionToTheSensor) {
  // A base turning on a 50 m circle, the LiDAR 1 m behind it and turned 90 deg: the baseline
  // follows the LiDAR's circle only with the extrinsic (to the sampling's first-order error).
  WheelOdometryParams params;
  params.extrinsic_rpy_deg = {0, 0, -90};  // the base's axes in the LiDAR frame
  params.extrinsic_xyz_m = {0, -1, 0};     // the base 1 m ahead, along the LiDAR's -y
  const Eigen::Isometry3d lidar_from_base =
      pose_from_rpy_xyz(params.extrinsic_rpy_deg.data(), params.extrinsic_xyz_m.data());
  std::vector<double> times;
  Poses truth;
  for (int i = 0; i <= 100; ++i) {
    times.push_back(0.1 * i);
    truth.push_back(arc(10.0, 0.2, 0.1 * i) * lidar_from_base.inverse());
  }
  const Poses with = wheel_baseline(truth, times, wheel_samples(10.0, 0.2, 10.0), params);
  EXPECT_LT((with.back().translation() - truth.back().translation()).norm(), 0.5);
  const Poses without =
      wheel_baseline(truth, times, wheel_samples(10.0, 0.2, 10.0), WheelOdometryParams{});
  EXPECT_GT((without.back().translation() - truth.back().translation()).norm(), 50.0);
}

TEST(Metrics, StepsWithinTheFirstSecond) {
  std::vector<double> times;
  for (int i = 0; i < 40; ++i)
    times.push_back(100.0 + 0.1 * i);
  EXPECT_EQ(steps_within(times, 1.0), 10u);
  for (double& time : times)
    time *= 0.5;  // 20 Hz
  EXPECT_EQ(steps_within(times, 1.0), 20u);
  EXPECT_EQ(steps_within({0.0}, 1.0), 0u);
}
