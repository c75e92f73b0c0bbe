// The start search's choice among the fits of a pair of scans taken at speed beside posts that
// repeat every 2 m: the truth and its aliases fit the posts alike; what does not repeat decides.

#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/odometry/start_search.h"
#include "support/scenes.h"

using namespace adaptive_lego_loam;
using test::Box;
using test::Scene;

namespace {

constexpr double kSpeed = 2.6;  // m between the scans (26 m/s)
constexpr double kAlias = 0.6;  // m: one post behind

// Posts every 2 m 6 m to either side of the road, and a few things that do not repeat: a sign
// gantry's leg, a cabinet, a parked van, a tree-like column.
Scene roadside() {
  Scene scene = test::post_rows(80.0);
  scene.boxes.push_back({{14.0, 9.0, -2.0}, {14.4, 9.4, 4.0}});
  scene.boxes.push_back({{-9.0, -8.5, -2.0}, {-7.8, -7.6, -0.3}});
  scene.boxes.push_back({{24.0, -11.5, -2.0}, {29.0, -9.5, 0.6}});
  scene.boxes.push_back({{-31.0, 12.0, -2.0}, {-30.4, 12.6, 5.0}});
  return scene;
}

// A lorry in the next lane, 3 m beside the sensor, driving kSpeed - kAlias a scan: relative to
// the sensor it moves by the alias.
Box lorry_at(double x) {
  return {{x - 6.0, 2.2, -1.7}, {x + 6.0, 4.7, 2.2}};
}

Eigen::Isometry3d along_x(double x) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation().x() = x;
  return pose;
}

// The non-ground points of `scene` seen from `pose`, as the odometry takes them. The ground is
// looked for on every row: the flat ground's rings, the same in every scan, would otherwise come
// in from beyond the ground rows and fit standing still.
CloudPtr points_seen(const Scene& scene, const Eigen::Isometry3d& pose) {
  SensorParams sensor = test::synthetic_config().sensor;
  sensor.ground_rows = sensor.rows;
  Segmenter segmenter(sensor, SegmentationParams());
  SegmentationResult segmentation;
  segmenter.process(test::render(sensor, scene, pose), segmentation);
  const SegmentedCloud& cloud = segmentation.cloud;
  return start_points(cloud.points, cloud.info.ground_flag, cloud.outliers);
}

struct Pair {
  PointKdTree first;
  CloudPtr second;
};

Pair pair_of(Scene first_scene, Scene second_scene) {
  Pair pair;
  pair.first.build(points_seen(first_scene, Eigen::Isometry3d::Identity()));
  pair.second = points_seen(second_scene, along_x(kSpeed));
  return pair;
}

int points_within(const Pair& pair, double x) {
  const Eigen::Isometry3f motion = along_x(x).cast<float>();
  int count = 0;
  uint32_t index;
  float squared;
  for (const CloudPoint& p : *pair.second)
    count += pair.first.nearest(motion * p.getVector3fMap(), 1, &index, &squared, 0.25f * 0.25f);
  return count;
}

}  // namespace

TEST(StartSearch, GuessesReachTheMaxSpeedInSteps) {
  OdometryParams params;
  params.start_search_max_speed = 40.0;
  params.start_search_step = 0.5;
  const std::vector<Eigen::Isometry3d> guesses = start_guesses(params, 0.1);
  ASSERT_EQ(guesses.size(), 9u);
  EXPECT_EQ(guesses.front().translation().norm(), 0.0);
  EXPECT_NEAR(guesses.back().translation().x(), 4.0, 1e-9);
}

TEST(StartSearch, OnlyPointsOffTheGroundCount) {
  std::vector<ScanPoint> points(4);
  std::vector<ScanPoint> outliers(2);
  const CloudPtr counted = start_points(points, {1, 0, 1, 0}, outliers);
  EXPECT_EQ(counted->size(), 4u);
}

TEST(StartSearch, TheTruthLaysMoreOfTheSceneOnTheFirstScanThanItsAliases) {
  const Pair pair = pair_of(roadside(), roadside());
  const double truth = overlap_area(pair.first, *pair.second, along_x(kSpeed), 0.25f);
  for (double alias : {0.0, kAlias, kSpeed + 2.0}) {
    EXPECT_GT(truth, overlap_area(pair.first, *pair.second, along_x(alias), 0.25f))
        << "alias " << alias;
  }
}

// A lorry beside the sensor that keeps pace with the alias has many more points than the few
// things that do not repeat, and counted point by point the alias wins; weighed by the surface
// they cover, the truth does.
TEST(StartSearch, ALorryKeepingPaceOutnumbersButDoesNotOutweighWhatDoesNotRepeat) {
  Scene first = roadside(), second = roadside();
  first.boxes.push_back(lorry_at(10.0));
  second.boxes.push_back(lorry_at(10.0 + kSpeed - kAlias));
  const Pair pair = pair_of(first, second);
  EXPECT_GT(points_within(pair, kAlias), points_within(pair, kSpeed))
      << "the premise: point by point, the lorry carries the alias";
  EXPECT_GT(overlap_area(pair.first, *pair.second, along_x(kSpeed), 0.25f),
            overlap_area(pair.first, *pair.second, along_x(kAlias), 0.25f));
}
