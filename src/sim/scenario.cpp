#include "adaptive_lego_loam/sim/scenario.h"

#include <stdexcept>

namespace adaptive_lego_loam::sim {

std::string kind_name(ScenarioKind kind) {
  switch (kind) {
    case ScenarioKind::kUrban:
      return "urban";
    case ScenarioKind::kHighway:
      return "highway";
    case ScenarioKind::kTunnel:
      return "tunnel";
    case ScenarioKind::kVegetation:
      return "vegetation";
    case ScenarioKind::kLoop:
      return "loop";
    case ScenarioKind::kCorridor:
      return "corridor";
  }
  return "unknown";
}

ScenarioParams default_scenario(ScenarioKind kind) {
  ScenarioParams p;
  p.kind = kind;
  p.name = kind_name(kind);
  switch (kind) {
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
      // Defaults of ScenarioParams: a two-lane street with parking lanes and sidewalks, houses and
      // blocks, and side streets at junctions about every 100 m.
      p.cruise_speed_mps = kind == ScenarioKind::kLoop ? 8.0 : 10.0;
      p.junctions_per_km = 10.0;
      break;
    case ScenarioKind::kHighway:
      // Two carriageways of three lanes, guard rails, sparse shrubs: weak constraint along x.
      p.road_half_width = 12.5;
      p.sidewalk_width = 0.0;
      p.ego_lateral = -6.125;
      p.cruise_speed_mps = 25.0;
      p.hill_amplitude_m = 3.0;
      p.hill_wavelength_m = 700.0;
      p.relief_amplitude_m = 0.1;
      p.relief_wavelength_m = 20.0;
      p.buildings = false;
      p.trees_per_100m = 0.8;
      p.bushes_per_100m = 4.0;
      p.poles_per_100m = 0.0;
      p.parked_car_share = 0.0;
      p.moving_cars_per_km_lane = 4.0;
      p.walkers_per_100m = 0.0;
      p.standing_people_per_100m = 0.0;
      p.fences_share = 0.0;
      p.guard_rails = true;
      break;
    case ScenarioKind::kTunnel:
      // A road tunnel of two lanes, a raised ledge on each side, entered from open road at
      // speed; inside, the drive brakes to 5 m/s and accelerates back. The approach has guard
      // rails, shrubs and trees in the fields and a cutting that deepens toward the portal.
      p.road_half_width = 4.5;
      p.sidewalk_width = 1.0;
      p.curb_height = 0.25;
      p.ego_lateral = -2.25;
      p.cruise_speed_mps = 15.0;
      p.speed_variation = 0.0;
      p.slow_speed_mps = 5.0;
      p.hill_amplitude_m = 0.5;
      p.hill_wavelength_m = 800.0;
      p.buildings = false;
      p.trees_per_100m = 3.0;
      p.bushes_per_100m = 10.0;
      p.poles_per_100m = 0.0;
      p.parked_car_share = 0.0;
      p.moving_cars_per_km_lane = 3.0;
      p.walkers_per_100m = 0.0;
      p.standing_people_per_100m = 0.0;
      p.fences_share = 0.0;
      p.guard_rails = true;
      p.tunnel = true;
      p.tunnel_furniture = true;
      p.tunnel_curve = true;
      break;
    case ScenarioKind::kVegetation:
      // A narrow, winding, hilly road through dense bushes and trees; a few walls; rough.
      p.road_half_width = 2.5;
      p.sidewalk_width = 0.0;
      p.ego_lateral = 0.0;
      p.cruise_speed_mps = 6.0;
      p.hill_amplitude_m = 4.0;
      p.hill_wavelength_m = 300.0;
      p.relief_amplitude_m = 0.3;
      p.relief_wavelength_m = 8.0;
      p.buildings = false;
      p.trees_per_100m = 20.0;
      p.bushes_per_100m = 90.0;
      p.poles_per_100m = 2.0;
      p.parked_car_share = 0.0;
      p.moving_cars_per_km_lane = 0.0;
      p.walkers_per_100m = 0.3;
      p.standing_people_per_100m = 0.0;
      p.walls_per_100m = 0.4;
      p.fences_share = 0.0;
      p.rough_road = true;
      break;
    case ScenarioKind::kCorridor:
      // An office building's corridors, 2 m wide (1.8-2.4 m is usual), doors every 10 m, a turn
      // into a second corridor; a robot's VLP-16 0.6 m above the floor at 1.5 m/s with stops.
      p.road_half_width = 1.0;
      p.sidewalk_width = 0.0;
      p.ego_lateral = 0.0;
      p.cruise_speed_mps = 1.5;
      p.speed_variation = 0.0;
      p.sensor_height_m = 0.6;
      p.hill_amplitude_m = 0.0;
      p.relief_amplitude_m = 0.0;
      p.buildings = false;
      p.trees_per_100m = 0.0;
      p.bushes_per_100m = 0.0;
      p.poles_per_100m = 0.0;
      p.parked_car_share = 0.0;
      p.moving_cars_per_km_lane = 0.0;
      p.walkers_per_100m = 0.0;
      p.standing_people_per_100m = 0.0;
      p.fences_share = 0.0;
      p.junctions_per_km = 0.0;
      break;
  }
  return p;
}

namespace {

// KITTI 01: a motorway whose verges are planted, shrubs and tree rows beside both carriageways
// (SemanticKITTI labels a tenth of its points vegetation or trunk and about 40 % terrain).
ScenarioParams green_highway() {
  ScenarioParams p = default_scenario(ScenarioKind::kHighway);
  p.name = "green_highway";
  p.planted_verges = true;
  p.bushes_per_100m = 45.0;
  p.trees_per_100m = 6.0;
  // Open verges and fields for the most part, guard rails in the median (SemanticKITTI: a few %
  // fence, no other structure).
  p.concrete_median_share = 0.2;
  p.noise_wall_share = 0.0;
  p.berm_share = 0.2;
  p.cutting_share = 0.1;
  return p;
}

// KITTI 04: a straight road through a small town at 14 m/s, lined with parked cars, people on the
// sidewalks, hedges and shrubs in the front gardens, poles and signs.
ScenarioParams busy_street() {
  ScenarioParams p = default_scenario(ScenarioKind::kUrban);
  p.name = "busy_street";
  p.cruise_speed_mps = 14.0;
  p.house_share = 1.0;
  p.parked_car_share = 0.2;
  p.moving_cars_per_km_lane = 10.0;
  p.walkers_per_100m = 6.0;
  p.standing_people_per_100m = 3.0;
  p.bushes_per_100m = 40.0;
  p.trees_per_100m = 10.0;
  p.poles_per_100m = 8.0;
  p.junctions_per_km = 3.0;
  return p;
}

// The tunnel without its furniture and curve: smooth walls and vault along a straight line, where
// nothing constrains the motion along the road (the limit case).
ScenarioParams bare_tunnel() {
  ScenarioParams p = default_scenario(ScenarioKind::kTunnel);
  p.name = "bare_tunnel";
  p.tunnel_furniture = false;
  p.tunnel_curve = false;
  return p;
}

}  // namespace

const std::vector<std::string>& scenario_names() {
  static const std::vector<std::string> names = {"urban",       "highway",     "tunnel",
                                                 "vegetation",  "loop",        "green_highway",
                                                 "busy_street", "bare_tunnel", "corridor"};
  return names;
}

ScenarioParams named_scenario(const std::string& name) {
  for (ScenarioKind kind :
       {ScenarioKind::kUrban, ScenarioKind::kHighway, ScenarioKind::kTunnel,
        ScenarioKind::kVegetation, ScenarioKind::kLoop, ScenarioKind::kCorridor}) {
    if (name == kind_name(kind)) return default_scenario(kind);
  }
  if (name == "green_highway") return green_highway();
  if (name == "busy_street") return busy_street();
  if (name == "bare_tunnel") return bare_tunnel();
  std::string allowed;
  for (const std::string& known : scenario_names())
    allowed += (allowed.empty() ? "" : ", ") + known;
  throw std::invalid_argument("unknown scenario '" + name + "': expected one of " + allowed);
}

}  // namespace adaptive_lego_loam::sim
