// The simulator's sensor model against analytic answers: ranges to a plane, a box and a cylinder,
// ring and time fields, motion distortion, noise, dropouts, intensity and labels.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/simulator.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

SensorParams vlp16() {
  return load_config(std::string(CONFIG_DIR) + "/vlp16.yaml").sensor;
}

SimSensorOptions exact_options(int columns) {
  SimSensorOptions options;
  options.columns = columns;
  options.range_noise_m = 0.0;
  options.motion_distortion = false;
  options.full_return_incidence_deg = 89.9;  // keep every return but the most grazing
  options.no_return_incidence_deg = 90.0;
  return options;
}

// A sensor standing still at `pose`.
std::shared_ptr<Trajectory> standing_at(
    const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) {
  return std::make_shared<SampledTrajectory>(std::vector<double>{0.0, 0.1, 0.2},
                                             std::vector<Eigen::Isometry3d>(3, pose), Shake());
}

// In-plane axes of a square facing `normal`.
std::pair<Eigen::Vector3f, Eigen::Vector3f> square_axes(const Eigen::Vector3f& normal) {
  const Eigen::Vector3f u = normal.unitOrthogonal();
  return {u, normal.cross(u).normalized()};
}

// A square of half size `half` centred on `centre`, facing `normal`.
void add_square(GeometrySet& set, const Eigen::Vector3f& centre, const Eigen::Vector3f& normal,
                float half, uint32_t surface) {
  const auto [axis_u, axis_v] = square_axes(normal);
  const Eigen::Vector3f u = half * axis_u, v = half * axis_v;
  set.add_quad(centre - u - v, centre + u - v, centre + u + v, centre - u + v, surface);
}

}  // namespace

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
