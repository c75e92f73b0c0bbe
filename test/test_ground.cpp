#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/ground.h"
#include "adaptive_lego_loam/core/range_image.h"
#include "adaptive_lego_loam/core/segmentation.h"
#include "synthetic.h"

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

TEST(Segmentation, SegmentedCloudHasGroundFlagsAndRowIndices) {
  SensorParams sensor = test::even_sensor(16, 900, -15.0, 15.0);
  sensor.ground_rows = 7;
  test::Scene scene;
  scene.has_ground = true;
  scene.ground_z = -1.0;
  scene.boxes.push_back({{6.0, -3.0, -1.0}, {6.3, 3.0, 2.0}});
  const Scan scan = test::render(sensor, scene);
  SegmentationParams params;
  Segmenter segmenter(sensor, params);
  SegmentationResult result;
  segmenter.process(scan, result);
  const SegmentedCloud& cloud = result.cloud;
  ASSERT_FALSE(cloud.points.empty());
  ASSERT_EQ(cloud.info.ground_flag.size(), cloud.points.size());
  ASSERT_EQ(cloud.info.column.size(), cloud.points.size());
  int ground = 0, wall = 0;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (cloud.info.ground_flag[i]) {
      ++ground;
      EXPECT_EQ(cloud.info.column[i] % params.ground_downsample, 0u);
    } else {
      ++wall;
      EXPECT_GT(cloud.points[i].x, 5.9f);
    }
  }
  EXPECT_GT(ground, 0);
  EXPECT_GT(wall, 100);
  // Rows are in order and start/end indices bracket each row's points (5 left out at each end).
  for (int row = 0; row < 16; ++row) {
    EXPECT_LE(cloud.info.start_ring_index[row], cloud.info.end_ring_index[row] + 11);
  }
  EXPECT_TRUE(std::is_sorted(cloud.row.begin(), cloud.row.end()));
  EXPECT_EQ(static_cast<int>(cloud.ground.size()), result.ground_points);
}
