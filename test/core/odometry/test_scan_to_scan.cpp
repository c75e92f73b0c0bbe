// Scan-to-scan odometry: two scans of a constructed scene taken a known rigid motion apart; the
// registration must recover that motion.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/odometry/feature_extraction.h"
#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/core/odometry/scan_to_scan.h"
#include "support/scenes.h"

using namespace adaptive_lego_loam;
using test::Box;
using test::Scene;

namespace {

// A yard: walls on four sides, a few pillars and a parked box, on flat ground 1.73 m below.
Scene yard() {
  Scene scene;
  scene.has_ground = true;
  scene.boxes = {
      {{18.0, -20.0, -2.0}, {18.5, 20.0, 4.0}}, {{-20.5, -20.0, -2.0}, {-20.0, 20.0, 4.0}},
      {{-20.0, 14.0, -2.0}, {18.0, 14.5, 3.0}}, {{-20.0, -16.5, -2.0}, {18.0, -16.0, 5.0}},
      {{6.0, 4.0, -2.0}, {6.6, 4.6, 3.0}},      {{-7.0, -6.0, -2.0}, {-6.4, -5.4, 3.0}},
      {{3.0, -8.0, -2.0}, {3.5, -7.5, 3.0}},    {{-4.0, 7.0, -2.0}, {-2.0, 9.0, -0.5}},
      {{10.0, -3.0, -2.0}, {10.4, -2.6, 3.0}}};
  return scene;
}

Eigen::Isometry3d motion_of(double x, double y, double yaw_deg) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() =
      Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  motion.translation() = Eigen::Vector3d(x, y, 0.0);
  return motion;
}

// The features of `scene` seen by a 16-beam sensor at `pose`.
FeatureSet features_in(const Scene& scene, const Eigen::Isometry3d& pose) {
  const SensorParams sensor = test::even_sensor(16, 1800, -15.0, 15.0);
  Segmenter segmenter(sensor, SegmentationParams());
  SegmentationResult segmentation;
  segmenter.process(test::render(sensor, scene, pose), segmentation);
  FeatureExtractor extractor{FeatureParams()};
  FeatureSet features;
  extractor.extract(segmentation.cloud, segmentation.cloud.points, segmentation.cloud.outliers,
                    features);
  return features;
}

FeatureSet features_at(const Eigen::Isometry3d& pose) {
  return features_in(yard(), pose);
}

// Within what mapping needs of its guess (it searches 1 m around each point). Not much tighter:
// with 16 beams 2 deg apart, a line through two edge points of neighbouring rows, each picked
// within half a column of the true edge, tilts by degrees, which costs scan-to-scan a few
// centimetres and a few tenths of a degree even on exact geometry.
void expect_recovered(const OdometryResult& result, const Eigen::Isometry3d& truth) {
  ASSERT_TRUE(result.registered);
  const Eigen::Isometry3d error = truth.inverse() * result.motion;
  EXPECT_LT(error.translation().norm(), 0.05)
      << "estimated " << result.motion.translation().transpose() << ", true "
      << truth.translation().transpose();
  EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, 0.5);
}

}  // namespace

TEST(ScanToScan, RecoversAKnownMotionFromNoGuess) {
  const Eigen::Isometry3d truth = motion_of(0.8, 0.15, 2.0);
  for (OdometryMode mode : {OdometryMode::kJoint, OdometryMode::kTwoStep}) {
    OdometryParams params;
    params.mode = mode;
    ScanToScanOdometry odometry(params);
    const OdometryResult first = odometry.register_scan(features_at(Eigen::Isometry3d::Identity()),
                                                        Eigen::Isometry3d::Identity());
    EXPECT_FALSE(first.registered) << "nothing to register the first scan to";
    const FeatureSet second = features_at(truth);
    ASSERT_GT(second.sharp->size(), 10u);
    ASSERT_GT(second.flat->size(), 10u);
    expect_recovered(odometry.register_scan(second, Eigen::Isometry3d::Identity()), truth);
  }
}

TEST(ScanToScan, ChainsMotionsScanAfterScanFromAConstantVelocityGuess) {
  OdometryParams params;
  ScanToScanOdometry odometry(params);
  const Eigen::Isometry3d step = motion_of(1.0, 0.05, -1.5);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  odometry.register_scan(features_at(pose), Eigen::Isometry3d::Identity());
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  for (int scan = 1; scan <= 3; ++scan) {
    pose = pose * step;
    const OdometryResult result = odometry.register_scan(features_at(pose), guess);
    expect_recovered(result, step);
    guess = result.motion;
  }
}

TEST(ScanToScan, TooFewFeaturesLeaveTheGuessUnregistered) {
  ScanToScanOdometry odometry{OdometryParams()};
  odometry.register_scan(features_at(Eigen::Isometry3d::Identity()), Eigen::Isometry3d::Identity());
  const Eigen::Isometry3d guess = motion_of(0.5, 0.0, 0.0);
  const OdometryResult result = odometry.register_scan(FeatureSet(), guess);
  EXPECT_FALSE(result.registered);
  EXPECT_TRUE(result.motion.isApprox(guess));
}

namespace {

// A road between rows of posts every 2 m, 6 m to either side, with a few objects that do not
// repeat: a sign, a cabinet, a parked van.
Scene post_rows() {
  Scene scene = test::post_rows(60.0);
  scene.boxes.push_back({{14.0, 7.0, -2.0}, {14.2, 9.5, 1.5}});
  scene.boxes.push_back({{-9.0, -8.5, -2.0}, {-7.8, -7.6, -0.3}});
  scene.boxes.push_back({{24.0, -9.5, -2.0}, {29.0, -7.5, 0.6}});
  return scene;
}

FeatureSet post_features_at(const Eigen::Isometry3d& pose) {
  return features_in(post_rows(), pose);
}

}  // namespace

// 2.6 m between two scans (26 m/s) beside posts every 2 m: from no motion the registration settles
// on the nearest alias, 0.6 m; from guesses every 0.5 m up to 4 m, each settles on its nearest fit,
// the truth among them.
TEST(ScanToScan, AlignedFromEachGuessBesideRepeatingPostsTheTruthIsAmongTheFits) {
  const Eigen::Isometry3d truth = motion_of(2.6, 0.0, 0.0);
  ScanToScanOdometry from_zero{OdometryParams()};
  from_zero.register_scan(post_features_at(Eigen::Isometry3d::Identity()),
                          Eigen::Isometry3d::Identity());
  const FeatureSet second = post_features_at(truth);
  const OdometryResult aliased = from_zero.register_scan(second, Eigen::Isometry3d::Identity());
  EXPECT_GT((aliased.motion.translation() - truth.translation()).norm(), 1.0)
      << "the premise: from zero the posts hold the registration on an alias, at "
      << aliased.motion.translation().transpose();

  ScanToScanOdometry searched{OdometryParams()};
  searched.register_scan(post_features_at(Eigen::Isometry3d::Identity()),
                         Eigen::Isometry3d::Identity());
  std::vector<Eigen::Isometry3d> guesses;
  for (double x = 0.0; x <= 4.0; x += 0.5)
    guesses.push_back(motion_of(x, 0.0, 0.0));
  const std::vector<OdometryResult> fits = searched.align_each(second, guesses);
  ASSERT_EQ(fits.size(), guesses.size());
  int at_truth = 0, at_alias = 0;
  for (const OdometryResult& fit : fits) {
    const double x = fit.motion.translation().x();
    at_truth += std::abs(x - 2.6) < 0.05;
    at_alias += std::abs(x - 0.6) < 0.2;  // pulled a little by what does not repeat
  }
  EXPECT_GT(at_truth, 0);
  EXPECT_GT(at_alias, 0);
  // Nothing was kept: the next registration is still against the first scan.
  expect_recovered(searched.register_scan(second, truth), truth);
}

namespace {

// The road between posts, and a lorry in the next lane, 3 m beside the sensor, keeping pace with
// it: it looks the same in both scans, so its correspondences say the sensor stood still, and
// along the road only the posts and a few objects say otherwise.
Scene road_with_lorry_beside(const Eigen::Isometry3d& sensor_pose) {
  Scene scene = post_rows();
  const double x = sensor_pose.translation().x();
  scene.boxes.push_back({{x - 6.0, 2.2, -1.7}, {x + 6.0, 4.7, 2.2}});
  return scene;
}

// An HDL-64E-like sensor: 64 beams 0.4 deg apart.
const SensorParams& dense_sensor() {
  static const SensorParams sensor = test::even_sensor(64, 2083, -24.8, 2.0);
  return sensor;
}

FeatureSet dense_features(const Scene& scene, const Eigen::Isometry3d& pose) {
  Segmenter segmenter(dense_sensor(), SegmentationParams());
  SegmentationResult segmentation;
  segmenter.process(test::render(dense_sensor(), scene, pose), segmentation);
  FeatureExtractor extractor{FeatureParams()};
  FeatureSet features;
  extractor.extract(segmentation.cloud, segmentation.cloud.points, segmentation.cloud.outliers,
                    features);
  return features;
}

double error_beside_a_lorry(const OdometryParams& params) {
  const Eigen::Isometry3d truth = motion_of(2.6, 0.0, 0.0);
  ScanToScanOdometry odometry(params, dense_sensor().beam_angles_deg);
  const Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  odometry.register_scan(dense_features(road_with_lorry_beside(start), start), start);
  const OdometryResult result =
      odometry.register_scan(dense_features(road_with_lorry_beside(truth), truth), truth);
  EXPECT_TRUE(result.registered);
  return (result.motion.translation() - truth.translation()).norm();
}

}  // namespace

// Weighed by the surface each point stands for, the lorry's many close points no longer outvote
// the road's posts: from the true motion as the guess, the estimate stays near it.
TEST(ScanToScan, RangeWeightingKeepsALorryKeepingPaceFromDraggingTheMotion) {
  OdometryParams unweighted;
  OdometryParams weighted;
  weighted.range_weight_fit_error = 0.1;
  const double dragged = error_beside_a_lorry(unweighted);
  const double kept = error_beside_a_lorry(weighted);
  std::printf("[ measured ] error beside a lorry: %.3f m unweighted, %.3f m weighted\n", dragged,
              kept);
  EXPECT_GT(dragged, 0.1) << "the premise: unweighted, the lorry drags the motion";
  EXPECT_LT(kept, 0.75 * dragged);
}

TEST(ScanToScan, WithoutBeamAnglesRangeWeightingChangesNothing) {
  const Eigen::Isometry3d truth = motion_of(0.8, 0.1, 3.0);
  OdometryParams weighted;
  weighted.range_weight_fit_error = 0.1;
  ScanToScanOdometry plain{OdometryParams()}, without_beams{weighted};
  const Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  plain.register_scan(features_at(start), start);
  without_beams.register_scan(features_at(start), start);
  const OdometryResult a = plain.register_scan(features_at(truth), start);
  const OdometryResult b = without_beams.register_scan(features_at(truth), start);
  EXPECT_TRUE(a.motion.isApprox(b.motion, 1e-12));
}

namespace {

// A corridor 6 m wide with smooth walls far past the sensor's reach both ways: nothing fixes the
// motion along it.
Scene corridor() {
  Scene scene;
  scene.has_ground = true;
  scene.boxes = {{{-200.0, 3.0, -2.0}, {200.0, 3.5, 4.0}},
                 {{-200.0, -3.5, -2.0}, {200.0, -3.0, 4.0}}};
  return scene;
}

}  // namespace

// The registration's information (what the pose's covariance is made of) says which way a smooth
// corridor leaves the motion open: along it. How little it knows there is overstated: the ends of
// each ring's wall at grazing incidence, 13-16 m ahead and behind, are taken for vertical edges
// that move with the sensor, and their lines claim the motion along the corridor to about 7 cm
// (the yard's weakest direction: 5 cm). Mapping discounts the scene's weak direction by mu; the
// odometry's covariance does not.
TEST(ScanToScan, TheInformationSaysWhichWayACorridorLeavesTheMotionOpen) {
  const Eigen::Isometry3d step = motion_of(1.0, 0.0, 0.0);
  const auto registered = [&](const Scene& scene) {
    ScanToScanOdometry odometry{OdometryParams()};
    const OdometryResult first =
        odometry.register_scan(features_in(scene, Eigen::Isometry3d::Identity()), step);
    EXPECT_TRUE(first.information.isZero()) << "nothing registered, nothing known";
    return odometry.register_scan(features_in(scene, step), step);
  };
  const OdometryResult yard_result = registered(yard());
  ASSERT_TRUE(yard_result.registered);
  const Observability yard_seen = observability(yard_result.information);
  EXPECT_LT(yard_seen.weakest_sigma(), 0.1);
  EXPECT_GT(std::abs(yard_seen.weakest_direction().z()), 0.9) << "the yard's walls fix x and y";

  const OdometryResult corridor_result = registered(corridor());
  ASSERT_TRUE(corridor_result.registered);
  const Observability seen = observability(corridor_result.information);
  EXPECT_GT(std::abs(seen.weakest_direction().x()), 0.95) << seen.weakest_direction().transpose();
  EXPECT_GT(seen.weakest_sigma(), yard_seen.weakest_sigma());
}

// Where the scene fixes the motion, the registration from the shifted guess comes back: nothing
// is held and the result is the one without the test, to the last bit.
TEST(ScanToScan, AScanThatFixesItsMotionIsNotHeld) {
  const Eigen::Isometry3d step = motion_of(0.8, 0.15, 2.0);
  OdometryParams params;
  params.follow_test_shift = 0.1;
  const auto registered = [&](const OdometryParams& with) {
    ScanToScanOdometry odometry{with};
    odometry.register_scan(features_in(yard(), Eigen::Isometry3d::Identity()), step);
    return odometry.register_scan(features_in(yard(), step), step);
  };
  const OdometryResult plain = registered(OdometryParams());
  const OdometryResult tested = registered(params);
  ASSERT_TRUE(tested.registered);
  EXPECT_FALSE(tested.held_direction);
  EXPECT_LT(std::abs(tested.follow), 0.2);
  EXPECT_TRUE(tested.motion.matrix() == plain.motion.matrix());
  EXPECT_TRUE(tested.information == plain.information);
}
