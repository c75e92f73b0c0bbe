#include "roadside_objects.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_lego_loam/sim/objects.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/terrain.h"

namespace adaptive_lego_loam::sim {

namespace {

// One house of an identical_houses street at `s` along the road; returns where the next lot
// starts.
double add_identical_house(Layout& l, double side, double s) {
  constexpr double kFrontage = 10.0, kDepth = 10.0, kHeight = 7.0, kSetback = 5.0, kGap = 6.0;
  const ScenarioParams& p = l.p;
  const double clearance = p.road_half_width + p.sidewalk_width + 0.3;
  const Path::Frame f = l.path.at(s + 0.5 * kFrontage);
  const Eigen::Vector2d centre =
      (f.position + side * (clearance + kSetback + 0.5 * kDepth) * f.left).head<2>();
  if (!l.claim(centre, f.heading, Eigen::Vector2d(0.5 * kFrontage, 0.5 * kDepth), clearance)) {
    return s + 4.0;
  }
  const Eigen::Vector3f base(centre.x(), centre.y(), l.terrain.height(centre) - 0.5);
  const uint32_t surface =
      l.world.add_surface(SemanticClass::kBuilding, l.world.new_instance(), 0.45f);
  add_building(l.world.tile_at(base), yaw_pose(base, static_cast<float>(f.heading)),
               Eigen::Vector3f(kFrontage, kDepth, kHeight + 0.5), 0.0f, surface);
  return s + kFrontage + kGap;
}

}  // namespace

void add_buildings(Layout& l, double side) {
  const ScenarioParams& p = l.p;
  const double clearance = p.road_half_width + p.sidewalk_width + 0.3;
  for (double s = l.start + l.rng.uniform(0.0, 10.0); s < l.length();) {
    if (p.identical_houses) {
      s = add_identical_house(l, side, s);
      continue;
    }
    const bool house = l.rng.chance(p.house_share);
    double frontage, depth, height, setback, yaw_offset;
    if (house) {
      frontage = l.rng.uniform(8.0, 14.0);
      depth = l.rng.uniform(8.0, 12.0);
      height = l.rng.uniform(6.0, 10.0);
      setback = l.rng.uniform(2.0, 9.0);
      yaw_offset =
          l.rng.chance(0.85) ? l.rng.normal(0.0, 0.05) : l.rng.sign() * l.rng.uniform(0.17, 0.5);
    } else {
      frontage = l.rng.uniform(15.0, 35.0);
      depth = l.rng.uniform(10.0, 18.0);
      height = l.rng.chance(0.2) ? l.rng.uniform(20.0, 40.0) : l.rng.uniform(9.0, 20.0);
      setback = l.rng.uniform(0.5, 4.0);
      yaw_offset = l.rng.normal(0.0, 0.015);
    }
    // Half the extent of the turned footprint across the street, to keep it off the sidewalk.
    const double reach =
        0.5 * (std::abs(std::sin(yaw_offset)) * frontage + std::abs(std::cos(yaw_offset)) * depth);
    const double lateral = side * (clearance + setback + reach);
    const Path::Frame f = l.path.at(s + 0.5 * frontage);
    const Eigen::Vector2d centre = (f.position + lateral * f.left).head<2>();
    const double yaw = f.heading + yaw_offset;
    if (!l.claim(centre, yaw, Eigen::Vector2d(0.5 * frontage, 0.5 * depth), clearance)) {
      s += 4.0;
      continue;
    }
    const Eigen::Vector2d along(std::cos(yaw), std::sin(yaw)),
        across(-std::sin(yaw), std::cos(yaw));
    double lowest = 1e9, highest = -1e9;
    for (double u : {-0.5, 0.5}) {
      for (double v : {-0.5, 0.5}) {
        const double z = l.terrain.height(centre + u * frontage * along + v * depth * across);
        lowest = std::min(lowest, z);
        highest = std::max(highest, z);
      }
    }
    const uint32_t surface = l.world.add_surface(SemanticClass::kBuilding, l.world.new_instance(),
                                                 static_cast<float>(l.rng.uniform(0.3, 0.6)));
    const Eigen::Vector3f base(centre.x(), centre.y(), lowest - 0.5);
    add_building(l.world.tile_at(base), yaw_pose(base, static_cast<float>(yaw)),
                 Eigen::Vector3f(frontage, depth, height + highest - lowest + 0.5),
                 !house && l.rng.chance(0.3) ? 1.5f : 0.0f, surface);
    double gap;
    if (house) {
      gap = l.rng.chance(0.2) ? l.rng.uniform(0.0, 1.0) : l.rng.uniform(3.0, 9.0);
    } else {
      gap = l.rng.chance(0.25) ? l.rng.uniform(8.0, 20.0) : l.rng.uniform(0.0, 3.0);
    }
    const double gap_start = s + frontage;
    if (house && gap > 1.0 && l.rng.chance(p.fences_share)) {
      // The boundary between two gardens: a fence from the sidewalk back past the house.
      const Path::Frame g = l.path.at(gap_start + 0.5 * gap);
      const double from = clearance + 0.3, to = clearance + setback + 2.0 * reach + 2.0;
      const Eigen::Vector2d start = (g.position + side * from * g.left).head<2>();
      const Eigen::Vector2d run = (side * g.left).head<2>();
      const double length = to - from;
      if (l.claim(start + 0.5 * length * run, std::atan2(run.y(), run.x()),
                  Eigen::Vector2d(0.5 * length, 0.1), clearance - 0.2)) {
        const uint32_t fence =
            l.world.add_surface(SemanticClass::kFence, l.world.new_instance(), 0.4f);
        add_fence(l.world.tile_at(l.at_ground(start)),
                  yaw_pose(l.at_ground(start), static_cast<float>(std::atan2(run.y(), run.x()))),
                  static_cast<float>(length), static_cast<float>(l.rng.uniform(1.0, 1.8)), fence);
      }
    }
    if (gap > 6.0) {
      if (l.rng.chance(p.fences_share)) {
        const Path::Frame g = l.path.at(gap_start + 0.5);
        const double fence_lateral = side * (clearance + 0.4);
        const Eigen::Vector2d start = (g.position + fence_lateral * g.left).head<2>();
        if (l.claim(start + 0.5 * (gap - 1.0) * g.forward.head<2>(), g.heading,
                    Eigen::Vector2d(0.5 * (gap - 1.0), 0.1), clearance - 0.2)) {
          const uint32_t fence =
              l.world.add_surface(SemanticClass::kFence, l.world.new_instance(), 0.4f);
          add_fence(l.world.tile_at(l.at_ground(start)), yaw_pose(l.at_ground(start), g.heading),
                    static_cast<float>(gap - 1.0), static_cast<float>(l.rng.uniform(1.2, 2.0)),
                    fence);
        }
      }
      const double lot = side * (clearance + l.rng.uniform(2.0, 8.0));
      l.add_plant(l.rng.chance(0.5) ? l.tree_prototypes : l.bush_prototypes,
                  l.beside(gap_start + 0.5 * gap, lot), 0.6, clearance);
    }
    s = gap_start + gap;
  }
}

void add_street_furniture(Layout& l, double side) {
  if (l.p.poles_per_100m <= 0.0) return;
  const double lateral = side * (l.p.road_half_width + 0.4);
  for (double s = l.start + l.rng.uniform(0.0, 20.0); s < l.length();
       s += l.step(l.p.poles_per_100m)) {
    const Path::Frame f = l.path.at(s);
    const Eigen::Vector2d xy = (f.position + lateral * f.left).head<2>();
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width + 0.5) ||
        !l.claim(xy, f.heading, Eigen::Vector2d(0.3, 0.3), 0.0))
      continue;
    const uint16_t instance = l.world.new_instance();
    const uint32_t pole = l.world.add_surface(SemanticClass::kPole, instance, 0.5f);
    const Eigen::Vector3f base = l.at_ground(xy);
    if (l.rng.chance(0.25)) {
      const uint32_t sign = l.world.add_surface(SemanticClass::kTrafficSign, instance, 0.9f);
      const Eigen::Vector3d facing = side < 0 ? -f.forward : f.forward;
      add_sign(l.world.tile_at(base), base, facing.cast<float>(), pole, sign);
    } else {
      add_street_light(l.world.tile_at(base), base, (-side * f.left).cast<float>(),
                       static_cast<float>(l.rng.uniform(6.5, 8.0)), 1.8f, pole);
    }
  }
}

void add_parked_cars(Layout& l, double side) {
  if (l.p.parked_car_share <= 0.0) return;
  const double lateral = side * (l.p.road_half_width - 1.2);
  for (double s = l.start + l.rng.uniform(0.0, 6.0); s < l.length(); s += l.rng.uniform(5.5, 7.0)) {
    if (!l.rng.chance(l.p.parked_car_share)) continue;
    const Path::Frame f = l.path.at(s);
    const Eigen::Vector2d xy =
        (f.position + (lateral + l.rng.uniform(-0.15, 0.15)) * f.left).head<2>();
    const CarShape shape = random_car_shape(l.rng.integer(0, kCarShapes - 1), l.rng);
    const double yaw = f.heading + (side > 0 ? M_PI : 0.0) + l.rng.normal(0.0, 0.03);
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width) ||
        !l.claim(xy, yaw, Eigen::Vector2d(0.5 * shape.length + 0.3, 0.5 * shape.width), 0.0))
      continue;
    const uint16_t instance = l.world.new_instance();
    const uint32_t body = l.world.add_surface(SemanticClass::kCar, instance,
                                              static_cast<float>(l.rng.uniform(0.2, 0.8)));
    const uint32_t wheels = l.world.add_surface(SemanticClass::kCar, instance, 0.1f);
    const Eigen::Vector3f base = l.at_ground(xy);
    add_car(l.world.tile_at(base), yaw_pose(base, static_cast<float>(yaw)), shape, body, wheels);
  }
}

void add_street_trees(Layout& l, double side) {
  if (l.p.trees_per_100m <= 0.0 || l.p.sidewalk_width <= 0.0) return;
  const double lateral = side * (l.p.road_half_width + 1.0);
  for (double s = l.start + l.rng.uniform(0.0, 10.0); s < l.length();
       s += l.step(l.p.trees_per_100m)) {
    const Eigen::Vector2d xy = l.beside(s, lateral);
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width + l.p.sidewalk_width)) continue;
    l.add_plant(l.tree_prototypes, xy, 0.5, l.p.road_half_width + 0.3);
  }
}

void add_front_gardens(Layout& l, double side) {
  if (l.p.bushes_per_100m <= 0.0 || l.p.sidewalk_width <= 0.0) return;
  const double clearance = l.p.road_half_width + l.p.sidewalk_width + 0.3;
  for (double s = l.start + l.rng.uniform(0.0, 10.0); s < l.length();
       s += l.step(l.p.bushes_per_100m)) {
    const Eigen::Vector2d xy = l.beside(s, side * (clearance + l.rng.uniform(0.3, 2.5)));
    l.add_plant(l.bush_prototypes, xy, 0.5, clearance);
  }
}

void add_standing_people(Layout& l, double side) {
  if (l.p.standing_people_per_100m <= 0.0) return;
  for (double s = l.start + l.rng.uniform(0.0, 50.0); s < l.length();
       s += l.step(l.p.standing_people_per_100m)) {
    const Path::Frame f = l.path.at(s);
    const double lateral =
        side * (l.p.road_half_width + l.p.sidewalk_width * l.rng.uniform(0.5, 0.9));
    const Eigen::Vector2d xy = (f.position + lateral * f.left).head<2>();
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width + l.p.sidewalk_width) ||
        !l.claim(xy, 0.0, Eigen::Vector2d(0.35, 0.35), 0.0))
      continue;
    const uint32_t surface =
        l.world.add_surface(SemanticClass::kPerson, l.world.new_instance(), 0.4f);
    const Eigen::Vector3f base = l.at_ground(xy);
    add_person(l.world.tile_at(base),
               yaw_pose(base, static_cast<float>(l.rng.uniform(0.0, 2.0 * M_PI))),
               static_cast<float>(l.rng.uniform(1.55, 1.9)), 0.0f, surface);
  }
}

void sweep_outline(Layout& l, double s0, double s1, double lateral,
                   const std::vector<Eigen::Vector2d>& outline, bool on_ground, uint32_t surface,
                   bool capped) {
  const double step = l.path.spacing();
  const int stations = std::max(1, static_cast<int>(std::ceil((s1 - s0) / step)));
  auto point = [&](const Path::Frame& f, double base, const Eigen::Vector2d& q) -> Eigen::Vector3f {
    Eigen::Vector3d p = f.position + (lateral + q.x()) * f.left;
    p.z() = base + q.y();
    return p.cast<float>();
  };
  auto base_of = [&](const Path::Frame& f) {
    return on_ground ? l.ground((f.position + lateral * f.left).head<2>()) : f.position.z();
  };
  Path::Frame a = l.path.at(s0);
  double base_a = base_of(a);
  // A convex outline's ends, as fans.
  const std::size_t corners = outline.size() - (outline.front() == outline.back() ? 1 : 0);
  auto cap = [&](const Path::Frame& f, double base) {
    GeometrySet& set = l.world.tile_at(point(f, base, outline.front()));
    for (std::size_t k = 1; k + 1 < corners; ++k) {
      set.add_triangle(point(f, base, outline[0]), point(f, base, outline[k]),
                       point(f, base, outline[k + 1]), surface);
    }
  };
  if (capped) cap(a, base_a);
  for (int i = 0; i < stations; ++i) {
    const Path::Frame b = l.path.at(s0 + (s1 - s0) * (i + 1) / stations);
    const double base_b = base_of(b);
    GeometrySet& set = l.world.tile_at(point(a, base_a, outline.front()));
    for (std::size_t k = 0; k + 1 < outline.size(); ++k) {
      set.add_quad(point(a, base_a, outline[k]), point(b, base_b, outline[k]),
                   point(b, base_b, outline[k + 1]), point(a, base_a, outline[k + 1]), surface);
    }
    a = b;
    base_a = base_b;
  }
  if (capped) cap(a, base_a);
}

void add_guard_rail(Layout& l, double lateral, double outward, double s0, double s1) {
  const uint32_t surface = l.world.add_surface(SemanticClass::kFence, l.world.new_instance(), 0.6f);
  const double spacing = l.path.spacing(), thickness = 0.08;
  const int first = static_cast<int>(std::floor(s0 / spacing));
  const int last = static_cast<int>(std::ceil(s1 / spacing));
  for (int i = first; i < last; ++i) {
    const Path::Frame a = l.path.at(i * spacing), b = l.path.at((i + 1) * spacing);
    auto point = [&](const Path::Frame& f, double d, double z) -> Eigen::Vector3f {
      Eigen::Vector3d p = f.position + d * f.left;
      p.z() += z;
      return p.cast<float>();
    };
    const double front = lateral, back = lateral + outward * thickness;
    const Eigen::Vector3f centre = point(a, lateral, 0.6);
    GeometrySet& set = l.world.tile_at(centre);
    set.add_quad(point(a, front, 0.5), point(b, front, 0.5), point(b, front, 0.8),
                 point(a, front, 0.8), surface);
    set.add_quad(point(a, front, 0.8), point(b, front, 0.8), point(b, back, 0.8),
                 point(a, back, 0.8), surface);
    set.add_quad(point(a, back, 0.5), point(b, back, 0.5), point(b, back, 0.8), point(a, back, 0.8),
                 surface);
    if (i % 2 == 0) {
      const Eigen::Vector3f post = point(a, back + outward * 0.06, -0.3);
      add_box(set, yaw_pose(post, static_cast<float>(a.heading)),
              Eigen::Vector3f(0.1f, 0.1f, 1.05f), surface);
    }
  }
}

}  // namespace adaptive_lego_loam::sim
