// The simulator's sensor model against analytic answers: ranges to a plane, a box and a cylinder,
// ring and time fields, motion distortion, noise, dropouts, intensity and labels.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/sim_sensors.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;
using namespace adaptive_lego_loam::sim::test;

TEST(SimSensorModel, RangeNoiseHasTheConfiguredSpread) {
  auto world = std::make_shared<World>();
  const uint32_t wall = world->add_surface(SemanticClass::kBuilding, 1, 0.5f);
  add_square(world->tile_at(Eigen::Vector3f(10, 0, 0)), Eigen::Vector3f(10, 0, 0),
             -Eigen::Vector3f::UnitX(), 40.0f, wall);
  const SensorParams sensor = vlp16();
  SimSensorOptions options = exact_options(1800);
  options.range_noise_m = 0.05;
  const SimFrame frame = render_one(sensor, options, world);
  ASSERT_GT(frame.scan.points.size(), 5000u);
  double sum = 0.0, squares = 0.0;
  for (const ScanPoint& p : frame.scan.points) {
    // Range error along the ray: distance to the wall over the ray's cosine to its normal.
    const Eigen::Vector3d point(p.x, p.y, p.z);
    const double error = (p.x - 10.0) / (point.x() / point.norm());
    sum += error;
    squares += error * error;
  }
  const double n = static_cast<double>(frame.scan.points.size());
  EXPECT_NEAR(sum / n, 0.0, 0.003);
  EXPECT_NEAR(std::sqrt(squares / n), 0.05, 0.003);
}

TEST(SimSensorModel, DropoutsAtGrazingIncidenceAndPastMaxRange) {
  auto world = std::make_shared<World>();
  const uint32_t ground = world->add_surface(SemanticClass::kRoad, 0, 0.2f);
  add_square(world->tile_at(Eigen::Vector3f::Zero()), Eigen::Vector3f(0, 0, -1.73f),
             Eigen::Vector3f::UnitZ(), 400.0f, ground);
  const SensorParams sensor = vlp16();
  SimSensorOptions options = exact_options(1800);
  options.full_return_incidence_deg = 70.0;
  options.no_return_incidence_deg = 86.0;
  const LidarModel model(sensor, options);
  const SimFrame frame = render_one(sensor, options, world);
  std::vector<int> per_ring(model.beams(), 0);
  for (const ScanPoint& p : frame.scan.points)
    ++per_ring[p.ring];
  for (int ring = 0; ring < model.beams(); ++ring) {
    const double elevation = sensor.beam_angles_deg[ring] * M_PI / 180.0;
    const double range = elevation < 0 ? 1.73 / std::sin(-elevation) : kInf;
    if (range > sensor.max_range) {  // upward, or past max range (-1 deg: 99 m at 89 deg)
      EXPECT_EQ(per_ring[ring], 0) << "ring " << ring;
      continue;
    }
    const double expected = model.return_probability(std::sin(-elevation)) * model.columns();
    EXPECT_NEAR(per_ring[ring], expected, 0.05 * model.columns()) << "ring " << ring;
  }
  EXPECT_GT(frame.scan.points.size(), 3000u);
}
