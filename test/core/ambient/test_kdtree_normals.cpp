#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/ambient/skeleton.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "core/ambient/filter_scan.h"
#include "support/scenes.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::test;
using test::Box;
using test::Scene;

TEST(KdTreeBaseline, AgreesOnTheCorridor) {
  const Config config = synthetic_config();
  const AmbientFilterResult result = filter(config, test::render(config.sensor, corridor()));
  std::vector<NormalFeature> normals;
  KdTreeNormalParams params;
  params.max_range = config.sensor.max_range;
  // Every 10th point keeps the test fast (the near walls are dense); the baseline proper uses all.
  const auto all_points = non_ground_points(result.segmentation);
  std::vector<ScanPoint> points;
  for (std::size_t i = 0; i < all_points.size(); i += 10)
    points.push_back(all_points[i]);
  kdtree_normals(points, params, normals);
  EXPECT_GT(normals.size(), result.normals.size());
  const Degeneration d = degeneration_from_normals(normals);
  ASSERT_TRUE(d.valid);
  EXPECT_GE(d.mu, 0.8);
}
