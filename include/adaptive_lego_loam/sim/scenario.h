#pragma once
// The scenarios the paper is about, and the scene generator that builds one from a seed along a
// synthetic path or a recorded trajectory.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/sim/smooth_trajectory.h"
#include "adaptive_lego_loam/sim/speed_profile.h"
#include "adaptive_lego_loam/sim/trajectory.h"
#include "adaptive_lego_loam/sim/world.h"

namespace adaptive_lego_loam::sim {

// How a scene is built (the path, the road's cross-section, the layout of its objects).
enum class ScenarioKind { kUrban, kHighway, kTunnel, kVegetation, kLoop, kCorridor };
// "urban", "highway", "tunnel", "vegetation", "loop", "corridor"
std::string kind_name(ScenarioKind kind);

// What a scenario's scene holds. Densities are per 100 m of road and per side.
struct ScenarioParams {
  std::string name = "urban";  // the scenario's name (scenario_names())
  ScenarioKind kind = ScenarioKind::kUrban;
  // Road: carriageway from -road_half_width to +road_half_width around the centreline.
  double road_half_width = 7.0;
  double sidewalk_width = 3.0;  // 0: none
  double curb_height = 0.15;
  double ego_lateral = -1.75;  // where the ego vehicle drives, left of the centreline (m)
  double cruise_speed_mps = 10.0;
  double speed_variation = 0.1;  // +- share of the cruise speed, over 20 s
  // > 0: inside a tunnel the drive brakes to this speed and accelerates back (speed_profile.h).
  double slow_speed_mps = 0.0;
  double sensor_height_m = 1.73;  // above the road or floor, unless the request sets another
  // Terrain: hills (amplitude of their sum, wavelength) and small relief off the road.
  double hill_amplitude_m = 2.0;
  double hill_wavelength_m = 400.0;
  double relief_amplitude_m = 0.05;
  double relief_wavelength_m = 10.0;
  // Objects.
  bool buildings = true;
  double trees_per_100m = 6.0;
  double bushes_per_100m = 12.0;
  double poles_per_100m = 3.0;
  double parked_car_share = 0.4;  // of parking slots taken (urban)
  double moving_cars_per_km_lane = 10.0;
  double walkers_per_100m = 3.0;
  double standing_people_per_100m = 1.0;
  double walls_per_100m = 0.0;
  // Highway verges planted along the road (green_highway): a belt of shrubs behind the guard rail
  // and rows of trees behind it, on open and berm stretches (a noise wall or cutting has none).
  bool planted_verges = false;
  // Highway stretches: the share with a concrete median barrier (else a double guard rail), and
  // of roadsides with a noise wall, a berm or a cutting (the rest open verges and fields).
  double concrete_median_share = 0.6;
  double noise_wall_share = 0.15;
  double berm_share = 0.15;
  double cutting_share = 0.2;
  double fences_share = 0.5;  // of gaps between buildings closed by a fence
  double house_share = 0.5;   // of building lots with a detached house rather than a block
  // Every lot the same detached house at the same spacing, without fences or garden plants: a
  // street where every place looks alike (place recognition must not take one for another).
  bool identical_houses = false;
  double junctions_per_km = 0.0;  // side streets branching off (urban)
  bool guard_rails = false;
  bool tunnel = false;
  // A road tunnel's furniture (lamps, emergency niches, signs, jet fans, a cable tray) and a
  // gentle curve inside it; without them, smooth walls and vault on a straight line.
  bool tunnel_furniture = false;
  bool tunnel_curve = false;
  // Vegetation: the leaf jitter from scan to scan (wind), and how dense the foliage is: a
  // multiple of each plant's extinction, with as many more leaf facets of the same size.
  double leaf_jitter_m = 0.04;
  double foliage_density = 1.0;
  int wind_states = 6;
  // A rough road: the vehicle's body shakes on its suspension, and the sensor with it.
  bool rough_road = false;
  ShakeParams shake;
};

ScenarioParams default_scenario(ScenarioKind kind);

// The named scenarios: one per kind ("urban", "highway", "tunnel", "vegetation", "loop",
// "corridor") and variants of a kind with other contents: "green_highway" (the highway with
// planted verges, shrub belts and tree rows on both sides, as KITTI 01), "busy_street" (a street
// crowded with parked and moving cars, people, hedges and street furniture, as KITTI 04) and
// "bare_tunnel" (the tunnel without furniture and curve: smooth walls, the limit case).
const std::vector<std::string>& scenario_names();
// Throws std::invalid_argument listing the names.
ScenarioParams named_scenario(const std::string& name);

struct SceneRequest {
  ScenarioParams scenario;
  // The scene, its path and the drive along it come from scene_seed (the seed when unset); the
  // seed alone then changes the moving objects, the rough road's shake, the wind and the
  // sensor's noise: the same place driven again.
  uint64_t seed = 1;
  std::optional<uint64_t> scene_seed;
  int laps = 1;  // a loop scenario goes round this many times in the requested frames
  int frames = 100;
  double frame_period = 0.1;
  std::optional<double> sensor_height;  // above the road; unset: the scenario's
  double reach = 120.0;                 // the sensor's maximum range: the scene extends this far
  // A recorded trajectory (vehicle axes: x forward, z up) with its times; empty: a synthetic path.
  std::vector<double> trajectory_times;
  std::vector<Eigen::Isometry3d> trajectory_poses;

  uint64_t scene() const { return scene_seed ? *scene_seed : seed; }
  double height() const { return sensor_height ? *sensor_height : scenario.sensor_height_m; }
};

struct GeneratedScene {
  std::shared_ptr<World> world;
  std::shared_ptr<const Path> path;
  // Where the sensor is: the drive's poses joined smoothly (SmoothTrajectory), its frames' poses
  // those of the drive (of a recorded one, smoothed to kRecordedCutoffHz).
  std::shared_ptr<const Trajectory> trajectory;
  // The same with its derivatives, for the IMU and the wheel odometry.
  std::shared_ptr<const SmoothTrajectory> motion;
  double path_length_m = 0.0;
  double drive_length_m = 0.0;             // driven over the requested frames
  std::vector<SpeedChange> speed_changes;  // of a synthetic drive's speed profile
  std::optional<double> tunnel_entry_m;    // how far the drive goes before the tunnel's portal
};

// A recorded trajectory's positions are smoothed to this cutoff: KITTI's ground truth carries
// centimetres of noise that, differentiated twice, would be accelerations of 10-50 m/s^2.
constexpr double kRecordedCutoffHz = 1.0;

// Throws std::invalid_argument when the request cannot be met (e.g. more frames than a recorded
// trajectory holds).
GeneratedScene generate_scene(const SceneRequest& request);

}  // namespace adaptive_lego_loam::sim
