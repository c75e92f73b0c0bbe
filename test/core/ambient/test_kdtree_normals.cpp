#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/ambient/skeleton.h"
#include "adaptive_lego_loam/core/clustering/euclidean_clustering.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "support/synthetic.h"

using namespace adaptive_lego_loam;
using test::Box;
using test::Scene;

namespace {

// HDL-64E-like layout, evenly spaced, ground possible in rows up to -3.5 deg.
Config synthetic_config() {
  Config config;
  config.sensor = test::even_sensor(64, 1800, -24.9, 2.0);
  config.sensor.ground_rows = 50;
  config.sensor.max_range = 100.0;
  return config;
}

Scene with_ground(std::vector<Box> boxes) {
  Scene scene;
  scene.has_ground = true;
  scene.ground_z = -1.73;
  scene.boxes = std::move(boxes);
  return scene;
}

Scene corridor() {
  return with_ground({{{-60, 2.8, -1.73}, {60, 3.0, 3.0}}, {{-60, -3.0, -1.73}, {60, -2.8, 3.0}}});
}

AmbientFilterResult filter(const Config& config, const Scan& scan) {
  AmbientFilter ambient(config);
  AmbientFilterResult result;
  ambient.process(scan, result);
  return result;
}

}  // namespace

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
