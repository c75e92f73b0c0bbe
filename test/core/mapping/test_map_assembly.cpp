// The saved map's layers: filtered tile by tile, they hold the same voxel centroids as one voxel
// filter of every keyframe's points.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "adaptive_lego_loam/core/mapping/map_assembly.h"
#include "adaptive_lego_loam/core/spatial/voxel_filter.h"

using namespace adaptive_lego_loam;

namespace {

Cloud scatter(std::mt19937& random, int count, double half_width) {
  std::uniform_real_distribution<float> across(-half_width, half_width), height(-2.f, 10.f);
  Cloud cloud;
  for (int i = 0; i < count; ++i) {
    CloudPoint p;
    p.x = across(random);
    p.y = across(random);
    p.z = height(random);
    p.intensity = static_cast<float>(i % 100);
    cloud.push_back(p);
  }
  return cloud;
}

// Keyframes 150 m apart along a diagonal, each with points up to 120 m around it: several tiles,
// on both sides of the origin, most reached by more than one keyframe.
std::vector<Keyframe> spread_keyframes() {
  std::mt19937 random(7);
  std::vector<Keyframe> keyframes(4);
  for (int i = 0; i < 4; ++i) {
    keyframes[i].index = i;
    keyframes[i].pose.translation() = Eigen::Vector3d(150.0 * i - 200.0, 100.0 * i - 150.0, 0.0);
    keyframes[i].corners = pack(scatter(random, 4000, 120.0));
    keyframes[i].surfaces = pack(scatter(random, 8000, 120.0));
  }
  keyframes[2].corners.reset();  // merged into another: adds nothing
  keyframes[2].surfaces.reset();
  return keyframes;
}

std::vector<std::tuple<float, float, float, float>> sorted(const Cloud& cloud) {
  std::vector<std::tuple<float, float, float, float>> points;
  for (const CloudPoint& p : cloud)
    points.emplace_back(p.x, p.y, p.z, p.intensity);
  std::sort(points.begin(), points.end());
  return points;
}

}  // namespace

TEST(MapAssembly, TileByTileGivesTheVoxelFilterOfEveryPoint) {
  const std::vector<Keyframe> keyframes = spread_keyframes();
  for (const MapLayer layer : {MapLayer::kAll, MapLayer::kCorners, MapLayer::kSurfaces}) {
    Cloud every_point;
    for (const Keyframe& keyframe : keyframes) {
      if (!keyframe.has_clouds()) continue;
      if (layer != MapLayer::kSurfaces) keyframe.corners->unpack(keyframe.pose, every_point);
      if (layer != MapLayer::kCorners) keyframe.surfaces->unpack(keyframe.pose, every_point);
    }
    const double leaf = 3.0;  // coarse: voxels with points of several keyframes
    const CloudPtr map = assemble_map(keyframes, layer, leaf);
    const CloudPtr reference = voxel_filter(every_point, leaf);
    ASSERT_GT(reference->size(), 1000u);
    // The same centroids, to the bit (each voxel's points are summed in the same order).
    EXPECT_EQ(sorted(*map), sorted(*reference)) << "layer " << static_cast<int>(layer);
    EXPECT_EQ(assemble_map(keyframes, layer, 0.0)->size(), every_point.size());
  }
}
