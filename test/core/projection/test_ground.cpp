#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/projection/ground.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;

TEST(Ground, FlatPlaneRowsAreGroundWallIsNot) {
  SensorParams sensor = test::even_sensor(16, 900, -15.0, 15.0);  // VLP-16 layout
  sensor.ground_rows = 7;
  test::Scene scene;
  scene.has_ground = true;
  scene.ground_z = -1.0;
  scene.boxes.push_back({{6.0, -3.0, -1.0}, {6.3, 3.0, 2.0}});  // a wall standing on the ground
  const Scan scan = test::render(sensor, scene);

  RangeProjector projector(sensor);
  RangeImage image;
  projector.project(scan, image);
  std::vector<uint8_t> ground;
  mark_ground(image, sensor.ground_rows, 0.0, 10.0, ground);

  int ground_hits = 0, ground_marked = 0, wall_hits = 0, wall_marked = 0;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (!image.occupied(cell)) continue;
    const ScanPoint& p = image.point(cell);
    const bool on_ground = std::fabs(p.z + 1.0) < 1e-3;
    // The lowest wall points pair with the ground beam below them at a shallow slope and are
    // ground by LeGO-LOAM's test; they are its foot, not the wall.
    const bool wall_foot = !on_ground && p.z < -0.85;
    const int row = image.row_of(cell);
    if (on_ground && row <= sensor.ground_rows) {
      ++ground_hits;
      ground_marked += ground[cell];
    } else if (!on_ground && !wall_foot) {
      ++wall_hits;
      wall_marked += ground[cell];
    }
  }
  ASSERT_GT(ground_hits, 1000);
  ASSERT_GT(wall_hits, 100);
  // Ground cells whose upper neighbour is the wall's foot can pair with either; allow those.
  EXPECT_GT(ground_marked, 0.97 * ground_hits);
  EXPECT_EQ(wall_marked, 0);
}

TEST(Ground, TiltedMountAngleIsRespected) {
  // A plane rising at 8 deg is ground for a sensor mounted at 8 deg, not for one mounted level
  // with a 5 deg tolerance.
  SensorParams sensor = test::even_sensor(16, 360, -15.0, 15.0);
  sensor.ground_rows = 7;
  Scan scan;
  scan.has_ring = true;
  const double slope = 8.0 * M_PI / 180.0;
  for (int row = 0; row < 8; ++row) {
    for (int col = 0; col < 360; ++col) {
      const Eigen::Vector3d dir = test::beam_direction(sensor, row, col);
      // plane z = -1 + tan(slope) * x
      const double t = -1.0 / (dir.z() - std::tan(slope) * dir.x());
      if (t > 0 && t < 90) scan.points.push_back(test::cell_point(sensor, row, col, t));
    }
  }
  RangeProjector projector(sensor);
  RangeImage image;
  projector.project(scan, image);
  std::vector<uint8_t> ground;
  // Only along +x (column 180) does the plane rise at exactly 8 deg along the beam plane.
  const int col = 180;
  mark_ground(image, 7, 8.0, 2.0, ground);
  EXPECT_TRUE(ground[image.cell(2, col)]);
  mark_ground(image, 7, 0.0, 5.0, ground);
  EXPECT_FALSE(ground[image.cell(2, col)]);
}

// Beams 0.18 deg apart (an OS2-128) see a wall 3.5 m away a centimetre apart in height, and 3 cm
// of range noise tilts such a pair to any slope: paired with the next row, a fifth of the wall
// is taken for ground. Paired with the first row 1 deg above, none is, and the road still is.
TEST(Ground, DenseBeamsPairedAcrossAGapDoNotTakeANoisyWallForGround) {
  SensorParams sensor = test::even_sensor(128, 360, -11.25, 11.25);
  sensor.ground_rows = 57;
  test::Scene scene;
  scene.has_ground = true;
  scene.ground_z = -1.73;
  scene.boxes.push_back({{3.5, -20.0, -1.73}, {3.6, 20.0, 5.0}});  // a wall beside the road
  Scan scan = test::render(sensor, scene);
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.f, 0.03f);
  for (ScanPoint& p : scan.points) {
    const float range = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    const float scale = (range + noise(rng)) / range;
    p.x *= scale;
    p.y *= scale;
    p.z *= scale;
  }
  RangeImage image;
  RangeProjector(sensor).project(scan, image);
  const auto wall_and_road_marked = [&](double row_gap_deg) {
    std::vector<uint8_t> ground;
    mark_ground(image, sensor.ground_rows, 0.0, 10.0, ground, row_gap_deg);
    int wall = 0, wall_marked = 0, road = 0, road_marked = 0;
    for (int cell = 0; cell < image.size(); ++cell) {
      if (!image.occupied(cell) || image.row_of(cell) > sensor.ground_rows) continue;
      const bool on_wall =
          image.point(cell).x > 3.4f && image.point(cell).z > -1.3f;  // not its foot
      const bool on_road = image.point(cell).z < -1.6f;
      wall += on_wall;
      wall_marked += on_wall && ground[cell];
      road += on_road;
      road_marked += on_road && ground[cell];
    }
    return std::make_pair(static_cast<double>(wall_marked) / wall,
                          static_cast<double>(road_marked) / road);
  };
  const auto [adjacent_wall, adjacent_road] = wall_and_road_marked(0.0);
  const auto [gap_wall, gap_road] = wall_and_road_marked(1.0);
  std::printf(
      "[ measured ] wall marked %.3f (adjacent rows), %.4f (1 deg apart); road %.3f, %.3f\n",
      adjacent_wall, gap_wall, adjacent_road, gap_road);
  EXPECT_GT(adjacent_wall, 0.05);
  EXPECT_LT(gap_wall, 0.001);
  EXPECT_GT(gap_road, 0.95);
}
