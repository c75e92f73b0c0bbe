// The simulator's sensor model against analytic answers: ranges to a plane, a box and a cylinder,
// ring and time fields, motion distortion, noise, dropouts, intensity and labels.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/sim_sensors.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

TEST(SimLabels, FoliageMovesBetweenScansAndCarriesItsInstance) {
  auto world = std::make_shared<World>();
  const uint32_t leaves = world->add_surface(SemanticClass::kVegetation, 0, 0.45f);
  const uint32_t wood = world->add_surface(SemanticClass::kTrunk, 0, 0.3f);
  const uint32_t wall = world->add_surface(SemanticClass::kBuilding, 2, 0.5f);
  Rng rng(5);
  world->plant_prototypes.push_back(
      make_plant(random_tree_shape(rng), 4, 0.04f, leaves, wood, rng));
  Plant plant;
  plant.base = Eigen::Vector3f(8.0f, 0.0f, -1.73f);
  plant.instance = 77;
  world->plants.push_back(plant);
  add_square(world->tile_at(Eigen::Vector3f(0, -12, 0)), Eigen::Vector3f(0, -12, 0),
             Eigen::Vector3f::UnitY(), 30.0f, wall);
  world->seed = 11;
  const SensorParams sensor = vlp16();
  LidarSimulator simulator(LidarModel(sensor, exact_options(1800)), world, standing_at(), 1);

  // Same pose, two scans: the wall returns the same points, the leaves do not.
  const SimFrame first = simulator.render(0), second = simulator.render(1);
  auto points_of = [](const SimFrame& frame, SemanticClass semantic) {
    std::vector<Eigen::Vector3f> points;
    for (std::size_t i = 0; i < frame.labels.size(); ++i) {
      if (label_class(frame.labels[i]) != semantic) continue;
      if (semantic == SemanticClass::kVegetation) {
        EXPECT_EQ(label_instance(frame.labels[i]), 77);
      }
      const ScanPoint& p = frame.scan.points[i];
      points.emplace_back(p.x, p.y, p.z);
    }
    return points;
  };
  const auto wall_first = points_of(first, SemanticClass::kBuilding);
  const auto wall_second = points_of(second, SemanticClass::kBuilding);
  const auto leaves_first = points_of(first, SemanticClass::kVegetation);
  const auto leaves_second = points_of(second, SemanticClass::kVegetation);
  ASSERT_GT(wall_first.size(), 500u);
  ASSERT_GT(leaves_first.size(), 200u);
  EXPECT_EQ(wall_first, wall_second);
  EXPECT_NE(leaves_first, leaves_second);
  EXPECT_GT(points_of(first, SemanticClass::kTrunk).size(), 5u);
}

// Beams stop sooner in denser foliage: the same tree at the default density returns from nearer
// its crown's surface than at a sixteenth of it (mean free path 0.09 m against 1.4 m), with
// leaves of the same size.
TEST(SimLabels, DenserFoliageStopsBeamsNearerTheCrownsSurface) {
  auto mean_leaf_range = [](double density) {
    auto world = std::make_shared<World>();
    const uint32_t leaves = world->add_surface(SemanticClass::kVegetation, 0, 0.45f);
    const uint32_t wood = world->add_surface(SemanticClass::kTrunk, 0, 0.3f);
    Rng rng(5);
    const PlantShape shape = with_foliage_density(random_tree_shape(rng), density);
    world->plant_prototypes.push_back(make_plant(shape, 1, 0.0f, leaves, wood, rng));
    Plant plant;
    plant.base = Eigen::Vector3f(8.0f, 0.0f, -1.73f);
    world->plants.push_back(plant);
    world->seed = 11;
    LidarSimulator simulator(LidarModel(vlp16(), exact_options(1800)), world, standing_at(), 1);
    const SimFrame frame = simulator.render(0);
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < frame.labels.size(); ++i) {
      if (label_class(frame.labels[i]) != SemanticClass::kVegetation) continue;
      const ScanPoint& p = frame.scan.points[i];
      sum += std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
      ++count;
    }
    EXPECT_GT(count, 100) << "density " << density;
    return sum / std::max(count, 1);
  };
  EXPECT_LT(mean_leaf_range(1.0), mean_leaf_range(0.0625) - 0.5);
  Rng rng(5);
  EXPECT_THROW(with_foliage_density(random_tree_shape(rng), 0.0), std::invalid_argument);
}
