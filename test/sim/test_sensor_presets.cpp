// The sensors lidar_sim models by name: each preset's config, and rings numbered as the sensor's
// driver numbers them.

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_lego_loam/sim/sensor_presets.h"
#include "sim_sensors.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

TEST(SensorPresets, EveryPresetModelsItsConfigsBeams) {
  for (const SensorPreset& preset : sensor_presets()) {
    SCOPED_TRACE(preset.name);
    const SensorParams sensor =
        load_config(std::string(CONFIG_DIR) + "/" + preset.config_file).sensor;
    const LidarModel model(sensor, preset_options(preset, sensor));
    EXPECT_EQ(model.beams(), sensor.rows);
    EXPECT_EQ(model.columns(), preset.firings > 0 ? preset.firings : sensor.columns);
    EXPECT_GT(model.options().range_noise_m, 0.0);
  }
  EXPECT_EQ(sensor_preset("hdl64e").firings, 2083);
  EXPECT_THROW(sensor_preset("os1_16"), std::invalid_argument);
}

// A simulated OS1-64 point carries ouster-ros's ring: 0 for the top beam.
TEST(SensorPresets, RingsAreTheDriversNumbering) {
  const SensorParams sensor = load_config(std::string(CONFIG_DIR) + "/os1_64.yaml").sensor;
  const LidarModel model(sensor, test::exact_options(sensor.columns));
  EXPECT_EQ(model.ring(0), 63);
  EXPECT_EQ(model.ring(63), 0);
  // A box of walls, floor and ceiling round the sensor: every beam comes back.
  auto world = std::make_shared<World>();
  const uint32_t surface = world->add_surface(SemanticClass::kBuilding, 0, 0.5f);
  const std::vector<Eigen::Vector3f> normals = {
      Eigen::Vector3f::UnitX(),  -Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY(),
      -Eigen::Vector3f::UnitY(), Eigen::Vector3f::UnitZ(),  -Eigen::Vector3f::UnitZ()};
  for (const Eigen::Vector3f& normal : normals) {
    const Eigen::Vector3f centre = -10.f * normal;
    test::add_square(world->tile_at(centre), centre, normal, 10.f, surface);
  }
  const SimFrame frame = test::render_one(sensor, test::exact_options(sensor.columns), world);
  ASSERT_GT(frame.scan.points.size(), 0.99 * sensor.rows * sensor.columns);
  for (const ScanPoint& p : frame.scan.points) {
    const double elevation = std::atan2(p.z, std::hypot(p.x, p.y)) * 180.0 / M_PI;
    ASSERT_NEAR(elevation, sensor.beam_angles_deg[sensor.ring_to_row[p.ring]], 1e-3);
  }
}
