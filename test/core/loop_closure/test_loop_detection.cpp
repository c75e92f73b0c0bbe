#include <gtest/gtest.h>
#include <pcl/registration/icp.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "adaptive_lego_loam/core/loop_closure/loop_detection.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"
#include "core/loop_closure/keyframe_scenes.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

bool same_bits(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), 16 * sizeof(double)) == 0;
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

void expect_same_detection(const LoopDetection& a, const LoopDetection& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.current_index, b.current_index);
  EXPECT_EQ(a.matched_index, b.matched_index);
  EXPECT_EQ(a.icp_iterations, b.icp_iterations);
  EXPECT_TRUE(same_bits(a.fitness, b.fitness)) << a.fitness << " vs " << b.fitness;
  EXPECT_TRUE(same_bits(a.correction, b.correction));
  EXPECT_TRUE(same_bits(a.relative_pose, b.relative_pose));
}

// A keyframe's clouds in the map frame.
Cloud placed(const Keyframe& keyframe) {
  Cloud cloud;
  keyframe.corners->unpack(keyframe.pose, cloud);
  keyframe.surfaces->unpack(keyframe.pose, cloud);
  return cloud;
}

// The current keyframe's points within verify_radius, placed by its pose (the radius search's
// guess).
Cloud verification_source(const Keyframe& keyframe, const LoopClosureParams& params) {
  Cloud sensor_frame;
  keyframe.corners->unpack(Eigen::Isometry3d::Identity(), sensor_frame);
  keyframe.surfaces->unpack(Eigen::Isometry3d::Identity(), sensor_frame);
  Cloud near;
  for (const CloudPoint& p : sensor_frame) {
    if (p.getVector3fMap().squaredNorm() <= params.verify_radius * params.verify_radius) {
      near.push_back(p);
    }
  }
  return *transform_cloud(near, keyframe.pose);
}

int radius_match(const std::vector<Keyframe>& keyframes, int current,
                 const LoopClosureParams& params) {
  const std::optional<LoopCandidate> candidate = radius_candidate(keyframes, current, params);
  return candidate ? candidate->matched_index : -1;
}

// What detect_loop documents, with PCL's ICP run in one align() on its own KD-tree.
LoopDetection pcl_one_shot(const std::vector<Keyframe>& keyframes, int current, int matched,
                           const LoopClosureParams& params) {
  const Cloud current_cloud = verification_source(keyframes[current], params);
  const std::size_t step =
      (current_cloud.size() + params.icp_max_points - 1) / params.icp_max_points;
  CloudPtr source(new Cloud);
  for (std::size_t i = 0; i < current_cloud.size(); i += std::max<std::size_t>(step, 1))
    source->push_back(current_cloud[i]);
  Cloud map;
  for (int i = std::max(0, matched - params.neighbourhood_keyframes);
       i <= std::min(current, matched + params.neighbourhood_keyframes); ++i) {
    if (i != current && keyframes[i].stamp <= keyframes[current].stamp - params.min_time_gap) {
      map += placed(keyframes[i]);
    }
  }
  pcl::IterativeClosestPoint<CloudPoint, CloudPoint> icp;
  icp.setMaxCorrespondenceDistance(params.icp_max_correspondence_distance);
  icp.setMaximumIterations(params.icp_max_iterations);
  icp.setTransformationEpsilon(1e-6);
  icp.setEuclideanFitnessEpsilon(1e-6);
  icp.setRANSACIterations(0);
  icp.setInputSource(source);
  icp.setInputTarget(voxel_filter(map, params.voxel_size));
  Cloud aligned;
  icp.align(aligned);
  LoopDetection loop;
  loop.fitness = icp.getFitnessScore();
  const Eigen::Matrix4d t = icp.getFinalTransformation().cast<double>();
  Eigen::Isometry3d transformation = Eigen::Isometry3d::Identity();
  transformation.linear() =
      Eigen::Quaterniond(t.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  transformation.translation() = t.topRightCorner<3, 1>();
  // As detect_loop: the corrected pose from the guess (here the pose), as a correction of it.
  const Eigen::Isometry3d& pose = keyframes[current].pose;
  loop.correction = (transformation * pose) * pose.inverse();
  return loop;
}

// The square drive whose last keyframe sees a different street: other boxes, same ground.
OffsetCase mismatched_case() {
  OffsetCase scene_case;
  const std::vector<Keyframe> elsewhere =
      keyframes_along(scene_case.truth, scene_case.estimates, 99);
  scene_case.keyframes[39].corners = elsewhere[39].corners;
  scene_case.keyframes[39].surfaces = elsewhere[39].surfaces;
  return scene_case;
}

}  // namespace

TEST(LoopClosure, CandidateIsNearestOldEnoughKeyframe) {
  const LoopClosureParams params;
  OffsetCase scene_case;
  std::vector<Keyframe>& keyframes = scene_case.keyframes;
  EXPECT_EQ(radius_match(keyframes, 39, params), 0);
  keyframes[39].pose.translation() << 3.2, 1.0, 0.0;
  EXPECT_EQ(radius_match(keyframes, 39, params), 3);
  // Keyframes 0-9 are the only ones 30 s older; none is within 7 m of (-8, 1).
  keyframes[39].pose.translation() << -8.0, 1.0, 0.0;
  EXPECT_EQ(radius_match(keyframes, 39, params), -1);
  EXPECT_EQ(detect_loop(keyframes, 39, params).status, LoopStatus::kNoCandidate);
  LoopClosureParams wide = params;
  wide.search_radius = 8.5;
  EXPECT_EQ(radius_match(keyframes, 39, wide), 0);
}

TEST(LoopClosure, RecentKeyframesAreNotCandidates) {
  OffsetCase scene_case;
  std::vector<Keyframe>& keyframes = scene_case.keyframes;
  for (Keyframe& keyframe : keyframes)
    keyframe.stamp = 0.5 * keyframe.index;  // the whole square in 19.5 s
  const LoopClosureParams params;
  EXPECT_EQ(radius_match(keyframes, 39, params), -1);
  EXPECT_EQ(detect_loop(keyframes, 39, params).status, LoopStatus::kNoCandidate);
  LoopClosureParams short_gap = params;
  short_gap.min_time_gap = 15.0;
  EXPECT_EQ(radius_match(keyframes, 39, short_gap), 0);
}

// The pose graph assumes a loop measurement good to its sigmas (0.2 m, 1 deg by default); ICP
// must recover the 1 m, 3 deg offset at least that well. (Point-to-point ICP with LeGO-LOAM's
// 100 m correspondence distance also pairs the points near the edge of the current view that the
// older keyframes never saw; in this scene that alone biases the result by about 0.12 m and
// 0.5 deg, even with no offset at all.)
TEST(LoopClosure, IcpRecoversOffsetOfLastKeyframe) {
  const OffsetCase scene_case;
  const LoopClosureParams params;
  const LoopDetection loop = detect_loop(scene_case.keyframes, 39, params);
  ASSERT_EQ(loop.status, LoopStatus::kAccepted)
      << to_string(loop.status) << ": " << loop.inlier_ratio << " inliers, mse " << loop.inlier_mse;
  EXPECT_EQ(loop.matched_index, 0);
  EXPECT_EQ(loop.current_index, 39);
  const Eigen::Isometry3d true_relative = scene_case.truth[0].inverse() * scene_case.truth[39];
  const Eigen::Isometry3d error = true_relative.inverse() * loop.relative_pose;
  std::printf(
      "[ measured ] loop: %.0f %% inliers, their mse %.4f m^2, relative pose off by %.4f m and "
      "%.3f deg, %.1f ms\n",
      100.0 * loop.inlier_ratio, loop.inlier_mse, error.translation().norm(), rotation_deg(error),
      loop.time_ms);
  EXPECT_GE(loop.inlier_ratio, params.min_inlier_ratio);
  EXPECT_LE(loop.inlier_mse, params.max_inlier_mse);
  EXPECT_LT(error.translation().norm(), params.loop_sigma_translation);
  EXPECT_LT(rotation_deg(error), params.loop_sigma_rotation_deg);
  // The correction undoes the offset: corrected pose = correction * estimate ~ truth.
  const Eigen::Isometry3d corrected = loop.correction * scene_case.estimates[39];
  EXPECT_LT((corrected.translation() - scene_case.truth[39].translation()).norm(),
            params.loop_sigma_translation);
}

// Refined on the planes of the candidate's map, the same loop is off by a fraction of ICP's
// error (ICP's bias above); the verification (inliers, fitness) stays ICP's.
TEST(LoopClosure, RefinementOnPlanesRemovesIcpsBias) {
  const OffsetCase scene_case;
  const LoopClosureParams params;
  const Eigen::Isometry3d true_relative = scene_case.truth[0].inverse() * scene_case.truth[39];
  const auto error_m = [&](const LoopDetection& loop) {
    return (true_relative.inverse() * loop.relative_pose).translation().norm();
  };
  const auto error_deg = [&](const LoopDetection& loop) {
    return rotation_deg(true_relative.inverse() * loop.relative_pose);
  };
  const std::optional<LoopCandidate> candidate = radius_candidate(scene_case.keyframes, 39, params);
  const LoopDetection icp = detect_loop(scene_case.keyframes, 39, candidate, params);
  const LoopDetection refined =
      detect_loop(scene_case.keyframes, 39, candidate, params, MappingParams());
  ASSERT_TRUE(icp.accepted());
  ASSERT_TRUE(refined.accepted());
  std::printf(
      "[ measured ] relative pose off by %.4f m, %.3f deg after ICP; %.4f m, %.3f deg refined "
      "(moved %.3f m), %.1f ms in all\n",
      error_m(icp), error_deg(icp), error_m(refined), error_deg(refined), refined.refinement_m,
      refined.time_ms);
  EXPECT_GT(error_m(icp), 0.05) << "the scene no longer shows ICP's bias";
  EXPECT_LT(error_m(refined), 0.03);
  EXPECT_LT(error_deg(refined), 0.15);
  EXPECT_GT(refined.refinement_m, 0.03);
  EXPECT_EQ(icp.refinement_m, 0.0);
  EXPECT_TRUE(same_bits(refined.fitness, icp.fitness));
  EXPECT_TRUE(same_bits(refined.inlier_ratio, icp.inlier_ratio));
  const Eigen::Isometry3d corrected = refined.correction * scene_case.estimates[39];
  EXPECT_LT((corrected.translation() - scene_case.truth[39].translation()).norm(), 0.03);
}

// A loop ICP rejects is not refined: nothing to refine, and no map built for it.
TEST(LoopClosure, ARejectedLoopIsNotRefined) {
  const OffsetCase scene_case = mismatched_case();
  const LoopClosureParams params;
  const LoopDetection loop =
      detect_loop(scene_case.keyframes, 39, radius_candidate(scene_case.keyframes, 39, params),
                  params, MappingParams());
  EXPECT_EQ(loop.status, LoopStatus::kTooFewInliers);
  EXPECT_EQ(loop.refinement_m, 0.0);
}

TEST(LoopClosure, MismatchedCloudIsRejectedForTooFewInliers) {
  const OffsetCase scene_case = mismatched_case();
  const LoopClosureParams params;
  const LoopDetection loop = detect_loop(scene_case.keyframes, 39, params);
  std::printf("[ measured ] mismatched cloud: %s, %.0f %% inliers, their mse %.3f m^2\n",
              to_string(loop.status), 100.0 * loop.inlier_ratio, loop.inlier_mse);
  EXPECT_EQ(loop.matched_index, 0);
  EXPECT_EQ(loop.status, LoopStatus::kTooFewInliers);
  EXPECT_TRUE(loop.inlier_ratio < params.min_inlier_ratio ||
              loop.inlier_mse > params.max_inlier_mse);
}

TEST(LoopClosure, EmptyCloudsAndDisabled) {
  OffsetCase scene_case;
  LoopClosureParams params;
  params.enabled = false;
  EXPECT_EQ(detect_loop(scene_case.keyframes, 39, params).status, LoopStatus::kDisabled);
  params.enabled = true;
  Keyframe& last = scene_case.keyframes[39];
  last.corners.reset();
  last.surfaces = pack(Cloud());
  EXPECT_EQ(detect_loop(scene_case.keyframes, 39, params).status, LoopStatus::kTooFewPoints);
  EXPECT_THROW(detect_loop(scene_case.keyframes, 40, params), std::out_of_range);
}

// The job's ICP resumes one iteration at a time, from the cloud the last one left, on
// PointKdTree: PCL's ICP in one align() on its own KD-tree gives the same fitness and
// transformation, bit for bit (the accepted loop and the mismatched cloud).
TEST(LoopClosure, SteppedIcpEqualsPclIcpInOneAlign) {
  const OffsetCase matching;
  const OffsetCase mismatched = mismatched_case();
  const LoopClosureParams params;
  for (const OffsetCase* scene_case : {&matching, &mismatched}) {
    const LoopDetection loop = detect_loop(scene_case->keyframes, 39, params);
    const LoopDetection reference = pcl_one_shot(scene_case->keyframes, 39, 0, params);
    std::printf("[ measured ] %s after %d ICP iterations, fitness %.6f (PCL in one align: %.6f)\n",
                to_string(loop.status), loop.icp_iterations, loop.fitness, reference.fitness);
    EXPECT_GT(loop.icp_iterations, 1);
    EXPECT_TRUE(same_bits(loop.fitness, reference.fitness));
    EXPECT_TRUE(same_bits(loop.correction, reference.correction));
  }
}

// Any step sizes give detect_loop's detection bit for bit; a step places keyframes up to
// map_points_per_scan points (at least one) and runs at most icp_iterations_per_scan iterations
// (the fitness counting as one); the voxel filter and the KD-tree take a step each.
TEST(LoopClosure, JobInStepsGivesTheOneShotDetection) {
  const OffsetCase scene_case;
  const LoopClosureParams params;
  const LoopDetection one_shot = detect_loop(scene_case.keyframes, 39, params);
  ASSERT_TRUE(one_shot.accepted());
  const int map_keyframes = 10;  // 0-9: the only ones 30 s older than 39
  for (const int iterations_per_step : {1, 2, 3, 7}) {
    LoopClosureParams stepped = params;
    stepped.map_points_per_scan = 1;
    stepped.icp_iterations_per_scan = iterations_per_step;
    LoopDetectionJob job(scene_case.keyframes, 39,
                         radius_candidate(scene_case.keyframes, 39, stepped), stepped);
    int steps = 0;
    while (!job.step())
      ++steps;
    ++steps;
    EXPECT_TRUE(job.step()) << "a finished job stays finished";
    expect_same_detection(job.detection(), one_shot);
    const int icp_pieces = one_shot.icp_iterations + 1;
    EXPECT_EQ(steps,
              map_keyframes + 2 + (icp_pieces + iterations_per_step - 1) / iterations_per_step)
        << iterations_per_step << " ICP iterations a step";
    EXPECT_GT(job.detection().time_ms, 0.0);
  }
}

// With the refinement, too: its map a keyframe a step at map_points_per_scan 1, then the match an
// iteration a step (at least two: the match stops on a small second step at the earliest).
TEST(LoopClosure, RefiningJobInStepsGivesTheOneShotDetection) {
  const OffsetCase scene_case;
  const LoopClosureParams params;
  const std::optional<LoopCandidate> candidate = radius_candidate(scene_case.keyframes, 39, params);
  const LoopDetection one_shot =
      detect_loop(scene_case.keyframes, 39, candidate, params, MappingParams());
  ASSERT_TRUE(one_shot.accepted());
  LoopClosureParams stepped = params;
  stepped.map_points_per_scan = 1;
  stepped.icp_iterations_per_scan = 1;
  LoopDetectionJob job(scene_case.keyframes, 39, candidate, stepped, MappingParams());
  int steps = 1;
  while (!job.step())
    ++steps;
  expect_same_detection(job.detection(), one_shot);
  EXPECT_TRUE(same_bits(job.detection().refinement_m, one_shot.refinement_m));
  const int map_keyframes = 10;
  const int before_match = map_keyframes + 2 + one_shot.icp_iterations + 1 + map_keyframes;
  EXPECT_GE(steps, before_match + 2);
  EXPECT_LE(steps, before_match + MappingParams().max_iterations);
}

TEST(LoopClosure, JobWithoutCandidateOrPointsIsDoneAtOnce) {
  OffsetCase scene_case;
  LoopClosureParams params;
  scene_case.keyframes[39].pose.translation() << -8.0, 1.0, 0.0;
  LoopDetectionJob no_candidate(scene_case.keyframes, 39, std::nullopt, params);
  EXPECT_TRUE(no_candidate.done());
  EXPECT_EQ(no_candidate.detection().status, LoopStatus::kNoCandidate);
  EXPECT_TRUE(no_candidate.step());

  OffsetCase empty;
  empty.keyframes[39].corners = pack(Cloud());
  empty.keyframes[39].surfaces = pack(Cloud());
  LoopDetectionJob too_few(empty.keyframes, 39, radius_candidate(empty.keyframes, 39, params),
                           params);
  EXPECT_TRUE(too_few.done());
  EXPECT_EQ(too_few.detection().status, LoopStatus::kTooFewPoints);
  EXPECT_EQ(too_few.detection().matched_index, 0);
  EXPECT_THROW(LoopDetectionJob(empty.keyframes, 40, std::nullopt, params), std::out_of_range);
}

// A loop that corrects the odometry by drift-sized amounts passes; one that would move the
// keyframe by hundreds of metres (a look-alike street driven the other way) does not, however
// well ICP fits it.
TEST(LoopClosure, DriftBoundKeepsDriftSizedCorrectionsAndRejectsLookAlikes) {
  std::vector<Keyframe> keyframes(801);
  for (int i = 0; i < 801; ++i) {
    keyframes[i].index = i;
    keyframes[i].pose.translation() = Eigen::Vector3d(i < 400 ? i : 800 - i, 0.0, 0.0);
  }
  LoopClosureParams params;  // 5 % of the path between the ends, plus 5 m
  LoopDetection loop;
  loop.status = LoopStatus::kAccepted;
  loop.matched_index = 0;
  loop.current_index = 800;  // back at the start after 800 m by the odometry
  // The loop says the keyframe is 30 m from where the odometry put it: 800 m x 5 % + 5 m allows 45.
  loop.relative_pose.translation() = Eigen::Vector3d(30.0, 0.0, 0.0);
  EXPECT_TRUE(within_drift_bound(keyframes, loop, params));
  loop.relative_pose.translation() = Eigen::Vector3d(0.0, 44.0, 0.0);
  EXPECT_TRUE(within_drift_bound(keyframes, loop, params));
  loop.relative_pose.translation() = Eigen::Vector3d(0.0, 46.0, 0.0);
  EXPECT_FALSE(within_drift_bound(keyframes, loop, params));
  // After only 40 m the same 30 m is no drift: 40 m x 5 % + 5 m allows 7.
  loop.matched_index = 760;
  loop.relative_pose = keyframes[760].pose.inverse() * keyframes[800].pose;
  loop.relative_pose.translation() += Eigen::Vector3d(6.0, 0.0, 0.0);
  EXPECT_TRUE(within_drift_bound(keyframes, loop, params));
  loop.relative_pose.translation() += Eigen::Vector3d(24.0, 0.0, 0.0);
  EXPECT_FALSE(within_drift_bound(keyframes, loop, params));
}

TEST(LoopClosure, ALoopNeedsAPathBetweenItsEnds) {
  // 30 keyframes jittering around one spot (a standstill, or odometry stalled in a tunnel), then
  // 100 m down a road and back: only the return is far enough along the path to close a loop.
  std::vector<Keyframe> keyframes;
  for (int i = 0; i < 30; ++i) {
    Keyframe keyframe;
    keyframe.index = i;
    keyframe.pose.translation() = Eigen::Vector3d(0.2 * (i % 2), 0.1 * (i % 3), 0.0);
    keyframes.push_back(keyframe);
  }
  for (int i = 1; i <= 200; ++i) {
    Keyframe keyframe;
    keyframe.index = static_cast<int>(keyframes.size());
    keyframe.pose.translation() = Eigen::Vector3d(i <= 100 ? i : 200 - i, 0.0, 0.0);
    keyframes.push_back(keyframe);
  }
  LoopClosureParams params;  // 40 m
  EXPECT_NEAR(path_between(keyframes, 29, 129), 100.0, 0.5);
  EXPECT_FALSE(far_enough_along(keyframes, 0, 29, params));
  EXPECT_TRUE(far_enough_along(keyframes, 0, static_cast<int>(keyframes.size()) - 1, params));
  EXPECT_FALSE(far_enough_along(keyframes, 200, 229, params));  // 29 m back along the road
}
