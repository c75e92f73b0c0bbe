// Place recognition: a candidate however far the drift has carried the current keyframe, with
// the relative yaw as ICP's guess, and the candidate verified by ICP.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/core/loop_closure/place_recognition.h"
#include "core/loop_closure/keyframe_scenes.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;

namespace {

LoopClosureParams params_for_this_scene() {
  LoopClosureParams params;
  params.place.max_radius = 20.0;  // what observe() sees
  return params;
}

// The square's keyframes with their places; the last one's estimate drifted `offset` away.
struct DriftedSquare {
  Poses truth = square_path();
  Poses estimates;
  std::vector<Keyframe> keyframes;
  PlaceRecognition places{params_for_this_scene()};
  explicit DriftedSquare(const Eigen::Isometry3d& offset) {
    estimates = truth;
    estimates.back() = offset * estimates.back();
    keyframes = keyframes_along(truth, estimates);
    // Descriptors from the scene sampled about as densely as a scan sees it nearby.
    std::vector<Patch> patches = scene(7);
    for (Patch& patch : patches)
      patch.density *= 10.0;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const CloudPtr seen = observe(patches, truth[k], 1000 + static_cast<unsigned>(k));
      places.add(static_cast<int>(k), keyframes[k].stamp,
                 places.describe({seen.get()}, keyframes[k].pose));
    }
  }
};

}  // namespace

TEST(PlaceRecognition, FindsThePlaceWhereTheRadiusSearchCannot) {
  // 15 m and 20 deg of drift: far beyond the radius search's 7 m.
  DriftedSquare square(planar(-12.0, 9.0, 20.0));
  const LoopClosureParams params = params_for_this_scene();
  EXPECT_FALSE(radius_candidate(square.keyframes, 39, params));
  const std::optional<LoopCandidate> candidate = square.places.candidate(square.keyframes, 39);
  ASSERT_TRUE(candidate);
  EXPECT_EQ(candidate->source, CandidateSource::kPlace);
  EXPECT_LE(candidate->matched_index, 1) << "keyframe 39 is 1 m from 0";
  EXPECT_LE(candidate->place_distance, params.place.max_distance);
  // The guess: at the matched keyframe, turned as keyframe 39 is really turned from it.
  const Eigen::Isometry3d true_relative =
      square.truth[candidate->matched_index].inverse() * square.truth[39];
  const Eigen::Isometry3d guess_relative =
      square.keyframes[candidate->matched_index].pose.inverse() * candidate->guess;
  EXPECT_NEAR(std::remainder(std::atan2(guess_relative(1, 0), guess_relative(0, 0)) -
                                 std::atan2(true_relative(1, 0), true_relative(0, 0)),
                             2 * M_PI) *
                  180.0 / M_PI,
              0.0, 6.0 + 1e-9);
  // ICP from that guess recovers the true relative pose, far better than the loop's sigmas.
  const LoopDetection loop = detect_loop(square.keyframes, 39, candidate, params);
  ASSERT_TRUE(loop.accepted()) << to_string(loop.status) << ", " << loop.inlier_ratio
                               << " inliers, mse " << loop.inlier_mse;
  const Eigen::Isometry3d error = true_relative.inverse() * loop.relative_pose;
  EXPECT_LT(error.translation().norm(), params.loop_sigma_translation);
  EXPECT_LT(rotation_deg(error), params.loop_sigma_rotation_deg);
}

TEST(PlaceRecognition, RecentPlacesAndForgottenOnesAreNoCandidates) {
  DriftedSquare square(planar(-12.0, 9.0, 20.0));
  square.places.forget(0, 9);  // keyframes 0-9, the only ones 30 s older than 39, driven again
  EXPECT_FALSE(square.places.candidate(square.keyframes, 39));
  EXPECT_FALSE(square.places.candidate(square.keyframes, 20)) << "its place was not added last";
}

TEST(PlaceRecognition, ForgottenPlacesLeaveTheOthersTheirOwnKeys) {
  // Each keyframe sees one post of its own, at a range that tells it apart (beyond 20 m none);
  // keyframe 39 sees keyframe 7's. With the places of 2-5 forgotten, and only the nearest ring key
  // compared in full, the candidate is still keyframe 7.
  LoopClosureParams params = params_for_this_scene();
  params.place.candidates = 1;
  const DriftedSquare square(planar(-12.0, 9.0, 20.0));  // the keyframes' stamps and poses
  PlaceRecognition places(params);
  for (int k = 0; k < 40; ++k) {
    Cloud post;
    for (double z = 0.0; z < 3.0; z += 0.1) {
      CloudPoint point;
      point.getVector3fMap() = Eigen::Vector3f(1.5f + (k == 39 ? 7 : k), 0.f, float(z));
      post.push_back(point);
    }
    places.add(k, square.keyframes[k].stamp, places.describe({&post}, square.keyframes[k].pose));
  }
  places.forget(2, 5);
  const std::optional<LoopCandidate> candidate = places.candidate(square.keyframes, 39);
  ASSERT_TRUE(candidate);
  EXPECT_EQ(candidate->matched_index, 7);
}
