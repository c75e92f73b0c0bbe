#include <gtest/gtest.h>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/projection/ground.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;

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
