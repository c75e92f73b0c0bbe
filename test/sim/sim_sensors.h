#pragma once
// Sensors and single-surface scenes for the simulator's tests.

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/sim/lidar_model.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "adaptive_lego_loam/sim/world.h"

namespace adaptive_lego_loam::sim::test {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline SensorParams vlp16() {
  return load_config(std::string(CONFIG_DIR) + "/vlp16.yaml").sensor;
}

inline SensorParams kitti_hdl64e() {
  return load_config(std::string(CONFIG_DIR) + "/kitti.yaml").sensor;
}

inline SimSensorOptions exact_options(int columns) {
  SimSensorOptions options;
  options.columns = columns;
  options.range_noise_m = 0.0;
  options.motion_distortion = false;
  options.full_return_incidence_deg = 89.9;  // keep every return but the most grazing
  options.no_return_incidence_deg = 90.0;
  return options;
}

// A sensor standing still at `pose`.
inline std::shared_ptr<Trajectory> standing_at(
    const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity()) {
  return std::make_shared<SampledTrajectory>(std::vector<double>{0.0, 0.1, 0.2},
                                             std::vector<Eigen::Isometry3d>(3, pose), Shake());
}

// A square of half size `half` centred on `centre`, facing `normal`.
// In-plane axes of a square facing `normal`.
inline std::pair<Eigen::Vector3f, Eigen::Vector3f> square_axes(const Eigen::Vector3f& normal) {
  const Eigen::Vector3f u = normal.unitOrthogonal();
  return {u, normal.cross(u).normalized()};
}

inline void add_square(GeometrySet& set, const Eigen::Vector3f& centre,
                       const Eigen::Vector3f& normal, float half, uint32_t surface) {
  const auto [axis_u, axis_v] = square_axes(normal);
  const Eigen::Vector3f u = half * axis_u, v = half * axis_v;
  set.add_quad(centre - u - v, centre + u - v, centre + u + v, centre - u + v, surface);
}

inline SimFrame render_one(const SensorParams& sensor, const SimSensorOptions& options,
                           std::shared_ptr<World> world,
                           std::shared_ptr<Trajectory> trajectory = standing_at(), int frame = 0,
                           uint64_t seed = 1) {
  LidarSimulator simulator(LidarModel(sensor, options), world, trajectory, seed);
  return simulator.render(frame);
}

}  // namespace adaptive_lego_loam::sim::test
