#include "traffic.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/sim/objects.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/terrain.h"
#include "placement.h"

namespace adaptive_lego_loam::sim {

namespace {

struct Lane {
  double lateral;
  double direction;  // +1 along the path
};

std::vector<Lane> traffic_lanes(const ScenarioParams& p) {
  switch (p.kind) {
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
      return {{-1.75, 1.0}, {1.75, -1.0}};
    case ScenarioKind::kHighway: {
      std::vector<Lane> lanes;
      for (double offset : {0.5 + 1.875, 0.5 + 5.625, 0.5 + 9.375}) {
        lanes.push_back({-offset, 1.0});
        lanes.push_back({offset, -1.0});
      }
      return lanes;
    }
    case ScenarioKind::kTunnel:
      return {{-2.25, 1.0}, {2.25, -1.0}};
    case ScenarioKind::kVegetation:
    case ScenarioKind::kCorridor:
      return {};
  }
  return {};
}

}  // namespace

void add_moving_cars(World& world, const Path& path, const ScenarioParams& p, double ego_start_s,
                     bool ego_lane_allowed, bool slows_down, Rng& rng) {
  if (p.moving_cars_per_km_lane <= 0.0) return;
  const uint32_t count_per_lane =
      static_cast<uint32_t>(std::lround(p.moving_cars_per_km_lane * path.length() / 1000.0));
  for (const Lane& lane : traffic_lanes(p)) {
    const bool ego_lane = std::abs(lane.lateral - p.ego_lateral) < 1.0;
    if (ego_lane && !ego_lane_allowed) continue;
    for (uint32_t i = 0; i < count_per_lane; ++i) {
      MovingCar car;
      car.prototype = rng.integer(0, kCarShapes - 1);
      car.instance = world.new_instance();
      car.motion.lateral = lane.lateral;
      car.motion.start_s = rng.uniform(0.0, path.length());
      double speed = p.cruise_speed_mps * rng.uniform(0.7, 1.2);
      if (ego_lane) {
        const bool ahead = car.motion.start_s > ego_start_s + 15.0;
        if (!ahead && (slows_down || car.motion.start_s > ego_start_s - 15.0)) continue;
        speed = p.cruise_speed_mps * (ahead ? rng.uniform(1.12, 1.3) : rng.uniform(0.7, 0.88));
      }
      car.motion.speed = lane.direction * speed;
      world.moving_cars.push_back(car);
    }
  }
}

void add_walkers(World& world, const Path& path, const ScenarioParams& p, Rng& rng) {
  if (p.walkers_per_100m <= 0.0) return;
  const uint32_t surface = world.add_surface(SemanticClass::kMovingPerson, 0, 0.4f);
  const int count = static_cast<int>(std::lround(p.walkers_per_100m * path.length() / 100.0 * 2.0));
  for (int i = 0; i < count; ++i) {
    Walker walker;
    const double side = rng.sign();
    walker.motion.lateral =
        p.sidewalk_width > 0.0
            ? side * (p.road_half_width + p.sidewalk_width * rng.uniform(0.3, 0.7))
            : side * (p.road_half_width - 0.4);
    walker.motion.start_s = rng.uniform(0.0, path.length());
    walker.motion.speed = rng.sign() * rng.uniform(1.0, 1.6);
    walker.height = static_cast<float>(rng.uniform(1.55, 1.9));
    walker.gait_phase = static_cast<float>(rng.uniform(0.0, 2.0 * M_PI));
    walker.instance = world.new_instance();
    walker.surface = surface;
    world.walkers.push_back(walker);
  }
}

}  // namespace adaptive_lego_loam::sim
