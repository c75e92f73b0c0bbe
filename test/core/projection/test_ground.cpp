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
