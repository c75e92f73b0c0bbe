#include "layouts.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/sim/objects.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/terrain.h"
#include "roadside_objects.h"

namespace adaptive_lego_loam::sim {

namespace {

// Along a side street: houses and blocks, parked cars, lights and trees; a building closes its
// far end.
void layout_side_street(Layout& main, const SideStreet& street, int owner) {
  const Path& path = *street.path;
  const Path::Frame end = path.at(path.length());
  const double heading = end.heading;
  ScenarioParams p = main.p;
  p.road_half_width = street.half_width;
  p.sidewalk_width = street.sidewalk_width;
  p.curb_height = street.curb_height;
  p.parked_car_share = 0.5 * main.p.parked_car_share;
  p.standing_people_per_100m = 0.0;
  Layout l{main.world, path,        main.terrain,         p,
           main.rng,   main.placer, main.tree_prototypes, main.bush_prototypes};
  l.start = street.corner + 6.0;
  l.owner = owner;
  for (double side : {-1.0, 1.0}) {
    add_parked_cars(l, side);
    add_street_furniture(l, side);
    add_street_trees(l, side);
    add_buildings(l, side);
    add_front_gardens(l, side);
  }
  // The building across its end.
  const double frontage = main.rng.uniform(16.0, 30.0), depth = main.rng.uniform(10.0, 16.0);
  const Eigen::Vector2d centre =
      end.position.head<2>() + (street.sidewalk_width + 2.0 + 0.5 * depth) * end.forward.head<2>();
  if (l.claim(centre, heading + 0.5 * M_PI, Eigen::Vector2d(0.5 * frontage, 0.5 * depth), 0.0)) {
    const uint32_t surface =
        main.world.add_surface(SemanticClass::kBuilding, main.world.new_instance(),
                               static_cast<float>(main.rng.uniform(0.3, 0.6)));
    const Eigen::Vector3f base(centre.x(), centre.y(), main.terrain.height(centre) - 0.5);
    add_building(main.world.tile_at(base), yaw_pose(base, static_cast<float>(heading + 0.5 * M_PI)),
                 Eigen::Vector3f(frontage, depth, main.rng.uniform(8.0, 18.0)), 0.0f, surface);
  }
}

}  // namespace

void layout_urban(Layout& l, const std::vector<SideStreet>& side_streets) {
  // The side streets' ground is theirs: nothing of the main street stands in their mouths.
  for (std::size_t i = 0; i < side_streets.size(); ++i) {
    const Path& street = *side_streets[i].path;
    const Path::Frame end = street.at(street.length());
    const double length = street.length() + 2.5;
    l.placer.reserve(
        street.at(0.0).position.head<2>() + (0.5 * length - 2.5) * end.forward.head<2>(),
        end.heading, Eigen::Vector2d(0.5 * length, side_streets[i].outer() + 0.3),
        static_cast<int>(i) + 1);
  }
  for (double side : {-1.0, 1.0}) {
    add_parked_cars(l, side);
    add_street_furniture(l, side);
    add_street_trees(l, side);
    add_standing_people(l, side);
    add_buildings(l, side);
    add_front_gardens(l, side);
  }
  for (std::size_t i = 0; i < side_streets.size(); ++i)
    layout_side_street(l, side_streets[i], static_cast<int>(i) + 1);
}

std::vector<HighwayStretch> plan_highway(const ScenarioParams& p, const Path& path, Rng& rng) {
  std::vector<HighwayStretch> stretches;
  const double open = 1.0 - p.noise_wall_share - p.berm_share - p.cutting_share;
  for (double s = 0.0; s < path.length();) {
    HighwayStretch stretch;
    stretch.s0 = s;
    stretch.s1 = std::min(path.length(), s + rng.uniform(250.0, 700.0));
    stretch.concrete_median = rng.chance(p.concrete_median_share);
    for (int side = 0; side < 2; ++side) {
      const double draw = rng.uniform();
      stretch.roadside[side] = draw < open                        ? Roadside::kOpen
                               : draw < open + p.noise_wall_share ? Roadside::kNoiseWall
                               : draw < 1.0 - p.cutting_share     ? Roadside::kBerm
                                                                  : Roadside::kCutting;
      stretch.height[side] = stretch.roadside[side] == Roadside::kNoiseWall ? rng.uniform(3.0, 5.0)
                                                                            : rng.uniform(2.5, 6.0);
    }
    stretches.push_back(stretch);
    s = stretch.s1;
  }
  return stretches;
}

std::vector<Berm> highway_berms(const std::vector<HighwayStretch>& stretches, double half_width) {
  std::vector<Berm> berms;
  for (const HighwayStretch& stretch : stretches) {
    for (int side = 0; side < 2; ++side) {
      if (stretch.roadside[side] != Roadside::kBerm && stretch.roadside[side] != Roadside::kCutting)
        continue;
      Berm berm;
      berm.s0 = stretch.s0;
      berm.s1 = stretch.s1;
      berm.side = side == 0 ? -1.0 : 1.0;
      berm.toe = half_width + kBermToeOffset;
      berm.height = stretch.height[side];
      // A cutting: the slope up to the level of the land around, which stays up.
      if (stretch.roadside[side] == Roadside::kCutting) berm.crest = 60.0;
      berms.push_back(berm);
    }
  }
  return berms;
}

namespace {

// A direction sign on two posts behind the guard rail, its board across the view along the road.
void add_roadside_sign(Layout& l, double s, double side) {
  const double w = l.p.road_half_width;
  const Path::Frame f = l.path.at(s);
  const float width = static_cast<float>(l.rng.uniform(2.5, 4.0));
  const float height = static_cast<float>(l.rng.uniform(1.6, 2.4));
  const Eigen::Vector2d centre = l.beside(s, side * (w + 1.0 + 0.5 * width));
  if (!l.claim(centre, f.heading, Eigen::Vector2d(0.4, 0.5 * width + 0.3), 0.0)) return;
  const uint16_t instance = l.world.new_instance();
  const uint32_t pole = l.world.add_surface(SemanticClass::kPole, instance, 0.5f);
  const uint32_t board = l.world.add_surface(SemanticClass::kTrafficSign, instance, 0.9f);
  const Eigen::Vector3f base = l.at_ground(centre);
  GeometrySet& set = l.world.tile_at(base);
  const Eigen::Vector3f across = f.left.cast<float>();
  for (float k : {-0.4f, 0.4f}) {
    const Eigen::Vector3f foot = base + k * width * across;
    set.add_prism(foot - Eigen::Vector3f(0, 0, 0.3f), foot + Eigen::Vector3f(0, 0, 2.0f + height),
                  0.05f, 8, pole);
  }
  add_box(set, yaw_pose(base + Eigen::Vector3f(0, 0, 2.0f), static_cast<float>(f.heading)),
          Eigen::Vector3f(0.05f, width, height), board);
}

// Planted verges (ScenarioParams::planted_verges): on each side of an open or berm stretch a belt
// of shrubs from 2 to 9 m behind the guard rail, broken by gaps, and rows of trees from 9 to 25 m.
// A noise wall or a cutting has no verge to plant.
void plant_verges(Layout& l, const std::vector<HighwayStretch>& stretches) {
  const double w = l.p.road_half_width;
  for (const HighwayStretch& stretch : stretches) {
    for (int index = 0; index < 2; ++index) {
      const Roadside roadside = stretch.roadside[index];
      if (roadside == Roadside::kNoiseWall || roadside == Roadside::kCutting) continue;
      const double side = index == 0 ? -1.0 : 1.0;
      for (double s = stretch.s0 + l.rng.uniform(0.0, 5.0); s < stretch.s1;) {
        // A stand of shrubs 10-60 m long, then a gap of 5-30 m.
        const double stand_end = std::min(stretch.s1, s + l.rng.uniform(10.0, 60.0));
        for (; s < stand_end; s += l.step(l.p.bushes_per_100m)) {
          l.add_plant(l.bush_prototypes, l.beside(s, side * (w + l.rng.uniform(2.0, 9.0))), 0.6,
                      w + 1.5);
        }
        s = stand_end + l.rng.uniform(5.0, 30.0);
      }
      for (double s = stretch.s0 + l.rng.uniform(0.0, 20.0); s < stretch.s1;
           s += l.step(l.p.trees_per_100m)) {
        l.add_plant(l.tree_prototypes, l.beside(s, side * (w + l.rng.uniform(9.0, 25.0))), 0.6,
                    w + 6.0);
      }
    }
  }
}

}  // namespace

void layout_highway(Layout& l, const std::vector<HighwayStretch>& stretches) {
  const double w = l.p.road_half_width;
  const std::vector<Eigen::Vector2d> barrier = {{-0.30, -0.05}, {-0.23, 0.075}, {-0.15, 0.33},
                                                {-0.075, 0.81}, {0.075, 0.81},  {0.15, 0.33},
                                                {0.23, 0.075},  {0.30, -0.05}};
  for (const HighwayStretch& stretch : stretches) {
    if (stretch.concrete_median) {
      const uint32_t concrete =
          l.world.add_surface(SemanticClass::kFence, l.world.new_instance(), 0.5f);
      sweep_outline(l, stretch.s0, stretch.s1, 0.0, barrier, false, concrete, true);
    } else {
      add_guard_rail(l, -0.35, 1.0, stretch.s0, stretch.s1);  // back to back
      add_guard_rail(l, 0.35, -1.0, stretch.s0, stretch.s1);
    }
    for (int index = 0; index < 2; ++index) {
      const double side = index == 0 ? -1.0 : 1.0;
      add_guard_rail(l, side * (w + 0.3), side, stretch.s0, stretch.s1);
      if (stretch.roadside[index] != Roadside::kNoiseWall) continue;
      const uint32_t wall =
          l.world.add_surface(SemanticClass::kOtherStructure, l.world.new_instance(), 0.4f);
      const double top = stretch.height[index];
      const double lateral = side * (w + kNoiseWallOffset);
      sweep_outline(l, stretch.s0, stretch.s1, lateral,
                    {{-0.1, -0.6}, {-0.1, top}, {0.1, top}, {0.1, -0.6}, {-0.1, -0.6}}, true, wall,
                    true);
      // Keep plants off it.
      for (double s = stretch.s0; s < stretch.s1; s += 10.0) {
        const Path::Frame f = l.path.at(s + 5.0);
        l.claim((f.position + lateral * f.left).head<2>(), f.heading, Eigen::Vector2d(5.0, 0.6),
                0.0);
      }
    }
  }
  for (double side : {-1.0, 1.0}) {
    for (double s = l.rng.uniform(100.0, 800.0); s < l.length(); s += l.rng.uniform(600.0, 1500.0))
      add_roadside_sign(l, s, side);
  }
  if (l.p.planted_verges) {
    plant_verges(l, stretches);
    return;
  }
  for (double side : {-1.0, 1.0}) {
    for (double s = l.rng.uniform(0.0, 30.0); s < l.length(); s += l.step(l.p.bushes_per_100m))
      l.add_plant(l.bush_prototypes, l.beside(s, side * (w + l.rng.uniform(3.0, 35.0))), 0.7,
                  w + 2.0);
    if (l.p.trees_per_100m <= 0.0) continue;
    for (double s = l.rng.uniform(0.0, 100.0); s < l.length(); s += l.step(l.p.trees_per_100m))
      l.add_plant(l.tree_prototypes, l.beside(s, side * (w + l.rng.uniform(10.0, 50.0))), 0.6,
                  w + 6.0);
  }
}

void layout_vegetation(Layout& l) {
  const double w = l.p.road_half_width;
  for (double side : {-1.0, 1.0}) {
    for (double s = l.rng.uniform(0.0, 3.0); s < l.length(); s += l.step(l.p.bushes_per_100m)) {
      // Densest along the road's edge, thinning out over 16 m.
      const double lateral = side * (w + 0.5 + std::pow(l.rng.uniform(), 2.0) * 16.0);
      l.add_plant(l.bush_prototypes, l.beside(s, lateral), 0.5, w + 0.4);
    }
    for (double s = l.rng.uniform(0.0, 8.0); s < l.length(); s += l.step(l.p.trees_per_100m)) {
      const double lateral = side * (w + 1.5 + std::pow(l.rng.uniform(), 1.3) * 45.0);
      l.add_plant(l.tree_prototypes, l.beside(s, lateral), 0.6, w + 1.0);
    }
    if (l.p.walls_per_100m <= 0.0) continue;
    for (double s = l.rng.uniform(0.0, 100.0); s < l.length(); s += l.step(l.p.walls_per_100m)) {
      const bool shed = l.rng.chance(0.3);
      const double length = shed ? 4.0 : l.rng.uniform(8.0, 20.0);
      const double depth = shed ? 3.0 : 0.4;
      const double lateral =
          side * (w + (shed ? l.rng.uniform(4.0, 10.0) : l.rng.uniform(1.5, 5.0)) + 0.5 * depth);
      const Path::Frame f = l.path.at(s + 0.5 * length);
      const Eigen::Vector2d centre = (f.position + lateral * f.left).head<2>();
      if (!l.claim(centre, f.heading, Eigen::Vector2d(0.5 * length, 0.5 * depth), w + 1.0))
        continue;
      const SemanticClass semantic =
          shed ? SemanticClass::kBuilding : SemanticClass::kOtherStructure;
      const uint32_t surface = l.world.add_surface(semantic, l.world.new_instance(), 0.35f);
      const Eigen::Vector3f base = l.at_ground(centre) - Eigen::Vector3f(0, 0, 0.5f);
      const double height = (shed ? 2.6 : l.rng.uniform(1.0, 2.2)) + 0.5;
      add_box(l.world.tile_at(base), yaw_pose(base, static_cast<float>(f.heading)),
              Eigen::Vector3f(length, depth, height), surface);
    }
  }
  // A line of power poles on one side.
  if (l.p.poles_per_100m > 0.0) {
    const double lateral = w + 2.0;
    for (double s = l.rng.uniform(0.0, 40.0); s < l.length(); s += l.step(l.p.poles_per_100m)) {
      const Path::Frame f = l.path.at(s);
      const Eigen::Vector2d xy = (f.position + lateral * f.left).head<2>();
      if (!l.claim(xy, 0.0, Eigen::Vector2d(0.3, 0.3), w + 1.0)) continue;
      const uint32_t surface =
          l.world.add_surface(SemanticClass::kPole, l.world.new_instance(), 0.3f);
      const Eigen::Vector3f base = l.at_ground(xy);
      add_power_pole(l.world.tile_at(base), base, f.left.cast<float>(), surface);
    }
  }
}

}  // namespace adaptive_lego_loam::sim
