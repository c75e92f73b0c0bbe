// Builds a scenario's World along a synthetic path or a recorded trajectory, from the seed alone.

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "adaptive_lego_loam/sim/objects.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/terrain.h"

namespace adaptive_lego_loam::sim {
namespace {

// Independent random streams, so that one part of the generator drawing more numbers does not
// change another part's scene.
enum Stream : uint64_t {
  kPathStream = 1,
  kHillStream,
  kPlantStream,
  kLayoutStream,
  kShakeStream,
  kMoverStream,
  kSpeedStream,
};

constexpr int kTreeShapes = 4, kBushShapes = 4, kCarShapes = 3;
constexpr double kUrbanTurnRadius = 14.0;
constexpr double kMinLoopLength = 160.0;

double lead_length(const SceneRequest& request) {
  return request.reach + 40.0;
}

// ---------------------------------------------------------------------------------------------
// Paths.

std::vector<PathPiece> open_pieces(ScenarioKind kind, double length, double lead, Rng& rng) {
  std::vector<PathPiece> pieces;
  double total = 0.0;
  auto add = [&](double piece_length, double curvature) {
    pieces.push_back({piece_length, curvature});
    total += piece_length;
  };
  switch (kind) {
    case ScenarioKind::kTunnel:
      add(length, 0.0);
      break;
    case ScenarioKind::kHighway:
      add(lead + rng.uniform(300.0, 800.0), 0.0);
      while (total < length) {
        const double radius = rng.uniform(1500.0, 3000.0);
        const double angle = rng.uniform(3.0, 10.0) * M_PI / 180.0;
        add(radius * angle, rng.sign() / radius);
        add(rng.uniform(400.0, 1200.0), 0.0);
      }
      break;
    case ScenarioKind::kVegetation: {
      add(lead + rng.uniform(10.0, 40.0), 0.0);
      double turn_sign = rng.sign();
      while (total < length) {
        const double radius = rng.uniform(35.0, 120.0);
        const double angle = rng.uniform(15.0, 70.0) * M_PI / 180.0;
        add(radius * angle, turn_sign / radius);
        add(rng.uniform(15.0, 70.0), 0.0);
        turn_sign = rng.chance(0.7) ? -turn_sign : turn_sign;
      }
      break;
    }
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
      add(lead + rng.uniform(40.0, 120.0), 0.0);
      while (total < length) {
        add(0.5 * M_PI * kUrbanTurnRadius, rng.sign() / kUrbanTurnRadius);
        add(rng.uniform(60.0, 160.0), 0.0);
      }
      break;
  }
  // Only as long as needed: terrain and objects are built along all of it.
  while (total - pieces.back().length >= length) {
    total -= pieces.back().length;
    pieces.pop_back();
  }
  pieces.back().length -= total - length;
  return pieces;
}

// A rounded rectangle (3:2) of the given length, counter-clockwise.
std::vector<PathPiece> loop_pieces(double length) {
  const double r = kUrbanTurnRadius;
  const double sides = (length - 2.0 * M_PI * r + 8.0 * r) / 2.0;  // a + b
  const double a = sides * 0.6, b = sides * 0.4;
  std::vector<PathPiece> pieces;
  for (int corner = 0; corner < 4; ++corner) {
    pieces.push_back({(corner % 2 == 0 ? a : b) - 2.0 * r, 0.0});
    pieces.push_back({0.5 * M_PI * r, 1.0 / r});
  }
  return pieces;
}

std::shared_ptr<const Path> synthetic_path(const std::vector<PathPiece>& pieces, bool closed,
                                           const HeightField& hills) {
  std::vector<Eigen::Vector3d> points = trace_pieces(pieces);
  if (closed) points.pop_back();  // the last point is the first again
  for (Eigen::Vector3d& point : points)
    point.z() = hills.at(point.head<2>());
  return std::make_shared<Path>(points, closed);
}

// The road under a recorded trajectory: the centreline lies `-ego_lateral` to the left of the
// vehicle, and runs on straight for `lead` metres before the first pose and after the last.
std::shared_ptr<const Path> recorded_path(const std::vector<Eigen::Isometry3d>& sensor_poses,
                                          double sensor_height, double ego_lateral, double lead) {
  std::vector<Eigen::Vector3d> centre;
  for (const Eigen::Isometry3d& pose : sensor_poses) {
    const Eigen::Vector3d forward = pose.linear().col(0);
    const Eigen::Vector3d left = Eigen::Vector3d(-forward.y(), forward.x(), 0.0).normalized();
    const Eigen::Vector3d point =
        pose * Eigen::Vector3d(0.0, 0.0, -sensor_height) - ego_lateral * left;
    if (centre.empty() || (point - centre.back()).head<2>().norm() >= 0.5) centre.push_back(point);
  }
  auto heading_of = [](const Eigen::Isometry3d& pose) -> Eigen::Vector3d {
    const Eigen::Vector3d forward = pose.linear().col(0);
    return Eigen::Vector3d(forward.x(), forward.y(), 0.0).normalized();
  };
  const Eigen::Vector3d first_forward =
      centre.size() > 1 ? Eigen::Vector3d((centre[1] - centre[0]).head<2>().normalized().x(),
                                          (centre[1] - centre[0]).head<2>().normalized().y(), 0.0)
                        : heading_of(sensor_poses.front());
  const Eigen::Vector3d last_forward =
      centre.size() > 1
          ? Eigen::Vector3d((centre.back() - centre[centre.size() - 2]).head<2>().normalized().x(),
                            (centre.back() - centre[centre.size() - 2]).head<2>().normalized().y(),
                            0.0)
          : heading_of(sensor_poses.back());
  std::vector<Eigen::Vector3d> points;
  for (double back = lead; back >= 1.0; back -= 1.0)
    points.push_back(centre.front() - back * first_forward);
  points.insert(points.end(), centre.begin(), centre.end());
  for (double ahead = 1.0; ahead <= lead; ahead += 1.0)
    points.push_back(centre.back() + ahead * last_forward);
  return std::make_shared<Path>(points, false);
}

// ---------------------------------------------------------------------------------------------
// Placing objects without overlaps and off the road.

class Placer {
 public:
  explicit Placer(const Path& path) : path_(path) {}

  // Takes an oriented rectangle of the ground when it overlaps nothing taken before and every
  // part of it keeps `road_clearance` from the path's centreline (0: no such check).
  bool claim(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half,
             double road_clearance) {
    const Eigen::Vector2d ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
    if (road_clearance > 0.0) {
      const int nx = static_cast<int>(std::ceil(2.0 * half.x())) + 1;
      const int ny = static_cast<int>(std::ceil(2.0 * half.y())) + 1;
      Path::Nearest unused;
      for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
          const Eigen::Vector2d p = centre + (-half.x() + 2.0 * half.x() * i / (nx - 1)) * ex +
                                    (-half.y() + 2.0 * half.y() * j / (ny - 1)) * ey;
          if (path_.nearest(p, road_clearance, unused)) return false;
        }
      }
    }
    std::vector<int64_t> cells;
    const double reach = half.norm();
    for (double x = std::floor((centre.x() - reach) / kCell); x * kCell <= centre.x() + reach;
         ++x) {
      for (double y = std::floor((centre.y() - reach) / kCell); y * kCell <= centre.y() + reach;
           ++y) {
        const Eigen::Vector2d offset =
            Eigen::Vector2d((x + 0.5) * kCell, (y + 0.5) * kCell) - centre;
        if (std::abs(offset.dot(ex)) > half.x() + 0.5 * kCell ||
            std::abs(offset.dot(ey)) > half.y() + 0.5 * kCell)
          continue;
        const int64_t key =
            (static_cast<int64_t>(x) << 32) ^ (static_cast<int64_t>(y) & 0xFFFFFFFFll);
        if (taken_.count(key)) return false;
        cells.push_back(key);
      }
    }
    taken_.insert(cells.begin(), cells.end());
    return true;
  }

 private:
  static constexpr double kCell = 0.5;
  const Path& path_;
  std::unordered_set<int64_t> taken_;
};

// What every layout needs while it places objects.
struct Layout {
  World& world;
  const Path& path;
  const TerrainModel& terrain;
  const ScenarioParams& p;
  Rng& rng;
  Placer& placer;
  std::vector<int> tree_prototypes, bush_prototypes;

  double length() const { return path.length(); }

  Eigen::Vector2d beside(double s, double lateral) const {
    const Path::Frame f = path.at(s);
    return (f.position + lateral * f.left).head<2>();
  }

  // Height of whatever a thing at xy stands on: road, sidewalk or terrain.
  double ground(const Eigen::Vector2d& xy) const {
    Path::Nearest nearest;
    if (path.nearest(xy, p.road_half_width + p.sidewalk_width, nearest)) {
      if (std::abs(nearest.lateral) <= p.road_half_width) return nearest.height;
      if (p.sidewalk_width > 0.0) return nearest.height + p.curb_height;
    }
    return terrain.height(xy);
  }

  Eigen::Vector3f at_ground(const Eigen::Vector2d& xy) const {
    return Eigen::Vector3f(xy.x(), xy.y(), ground(xy));
  }

  // The next arc length of a sequence with `per_100m` items on average.
  double step(double per_100m) { return 100.0 / per_100m * rng.uniform(0.4, 1.6); }

  void add_plant(const std::vector<int>& prototypes, const Eigen::Vector2d& xy, double footprint,
                 double road_clearance) {
    if (!placer.claim(xy, 0.0, Eigen::Vector2d::Constant(footprint), road_clearance)) return;
    Plant plant;
    plant.prototype = prototypes[rng.integer(0, static_cast<int>(prototypes.size()) - 1)];
    plant.base = at_ground(xy);
    plant.yaw = static_cast<float>(rng.uniform(0.0, 2.0 * M_PI));
    plant.scale = static_cast<float>(rng.uniform(0.8, 1.25));
    plant.instance = world.new_instance();
    plant.sway_phase = static_cast<float>(rng.uniform(0.0, 2.0 * M_PI));
    world.plants.push_back(plant);
  }
};

// ---------------------------------------------------------------------------------------------
// Objects common to several scenarios.

void add_buildings(Layout& l, double side) {
  const ScenarioParams& p = l.p;
  const double clearance = p.road_half_width + p.sidewalk_width + 0.3;
  for (double s = l.rng.uniform(0.0, 10.0); s < l.length();) {
    const double frontage = l.rng.uniform(10.0, 30.0), depth = l.rng.uniform(10.0, 22.0);
    const double height = l.rng.chance(0.2) ? l.rng.uniform(20.0, 40.0) : l.rng.uniform(6.0, 20.0);
    const double setback = l.rng.uniform(0.5, 4.0);
    const double lateral = side * (clearance + setback + 0.5 * depth);
    const Path::Frame f = l.path.at(s + 0.5 * frontage);
    const Eigen::Vector2d centre = (f.position + lateral * f.left).head<2>();
    if (!l.placer.claim(centre, f.heading, Eigen::Vector2d(0.5 * frontage, 0.5 * depth),
                        clearance)) {
      s += 4.0;
      continue;
    }
    double lowest = 1e9, highest = -1e9;
    for (double u : {-0.5, 0.5}) {
      for (double v : {-0.5, 0.5}) {
        const double z = l.terrain.height(centre + u * frontage * f.forward.head<2>() +
                                          v * depth * f.left.head<2>());
        lowest = std::min(lowest, z);
        highest = std::max(highest, z);
      }
    }
    const uint32_t surface = l.world.add_surface(SemanticClass::kBuilding, l.world.new_instance(),
                                                 static_cast<float>(l.rng.uniform(0.3, 0.6)));
    const Eigen::Vector3f base(centre.x(), centre.y(), lowest - 0.5);
    add_building(l.world.tile_at(base), yaw_pose(base, f.heading),
                 Eigen::Vector3f(frontage, depth, height + highest - lowest + 0.5),
                 l.rng.chance(0.3) ? 1.5f : 0.0f, surface);
    const double gap = l.rng.chance(0.25) ? l.rng.uniform(8.0, 20.0) : l.rng.uniform(0.0, 3.0);
    const double gap_start = s + frontage;
    if (gap > 6.0) {
      if (l.rng.chance(p.fences_share)) {
        const Path::Frame g = l.path.at(gap_start + 0.5);
        const double fence_lateral = side * (clearance + 0.4);
        const Eigen::Vector2d start = (g.position + fence_lateral * g.left).head<2>();
        if (l.placer.claim(start + 0.5 * (gap - 1.0) * g.forward.head<2>(), g.heading,
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

// Street lights (and some traffic signs) at the edge of the road.
void add_street_furniture(Layout& l, double side) {
  if (l.p.poles_per_100m <= 0.0) return;
  const double lateral = side * (l.p.road_half_width + 0.4);
  for (double s = l.rng.uniform(0.0, 20.0); s < l.length(); s += l.step(l.p.poles_per_100m)) {
    const Path::Frame f = l.path.at(s);
    const Eigen::Vector2d xy = (f.position + lateral * f.left).head<2>();
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width + 0.5) ||
        !l.placer.claim(xy, f.heading, Eigen::Vector2d(0.3, 0.3), 0.0))
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
  for (double s = l.rng.uniform(0.0, 6.0); s < l.length(); s += l.rng.uniform(5.5, 7.0)) {
    if (!l.rng.chance(l.p.parked_car_share)) continue;
    const Path::Frame f = l.path.at(s);
    const Eigen::Vector2d xy =
        (f.position + (lateral + l.rng.uniform(-0.15, 0.15)) * f.left).head<2>();
    const CarShape shape = random_car_shape(l.rng.integer(0, kCarShapes - 1), l.rng);
    const double yaw = f.heading + (side > 0 ? M_PI : 0.0) + l.rng.normal(0.0, 0.03);
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width) ||
        !l.placer.claim(xy, yaw, Eigen::Vector2d(0.5 * shape.length + 0.3, 0.5 * shape.width), 0.0))
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
  for (double s = l.rng.uniform(0.0, 10.0); s < l.length(); s += l.step(l.p.trees_per_100m)) {
    const Eigen::Vector2d xy = l.beside(s, lateral);
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width + l.p.sidewalk_width)) continue;
    l.add_plant(l.tree_prototypes, xy, 0.5, l.p.road_half_width + 0.3);
  }
}

// Bushes and hedges in the strip between the sidewalk and the buildings.
void add_front_gardens(Layout& l, double side) {
  if (l.p.bushes_per_100m <= 0.0 || l.p.sidewalk_width <= 0.0) return;
  const double clearance = l.p.road_half_width + l.p.sidewalk_width + 0.3;
  for (double s = l.rng.uniform(0.0, 10.0); s < l.length(); s += l.step(l.p.bushes_per_100m)) {
    const Eigen::Vector2d xy = l.beside(s, side * (clearance + l.rng.uniform(0.3, 2.5)));
    l.add_plant(l.bush_prototypes, xy, 0.5, clearance);
  }
}

void add_standing_people(Layout& l, double side) {
  if (l.p.standing_people_per_100m <= 0.0) return;
  for (double s = l.rng.uniform(0.0, 50.0); s < l.length();
       s += l.step(l.p.standing_people_per_100m)) {
    const Path::Frame f = l.path.at(s);
    const double lateral =
        side * (l.p.road_half_width + l.p.sidewalk_width * l.rng.uniform(0.5, 0.9));
    const Eigen::Vector2d xy = (f.position + lateral * f.left).head<2>();
    if (on_other_stretch(l.path, xy, s, l.p.road_half_width + l.p.sidewalk_width) ||
        !l.placer.claim(xy, 0.0, Eigen::Vector2d(0.35, 0.35), 0.0))
      continue;
    const uint32_t surface =
        l.world.add_surface(SemanticClass::kPerson, l.world.new_instance(), 0.4f);
    const Eigen::Vector3f base = l.at_ground(xy);
    add_person(l.world.tile_at(base),
               yaw_pose(base, static_cast<float>(l.rng.uniform(0.0, 2.0 * M_PI))),
               static_cast<float>(l.rng.uniform(1.55, 1.9)), 0.0f, surface);
  }
}

// A guard rail along the path `lateral` m left of the centreline; its posts stand on the side
// `outward` (+1: left) of the rail, behind it as seen from the road.
void add_guard_rail(Layout& l, double lateral, double outward) {
  const uint32_t surface = l.world.add_surface(SemanticClass::kFence, l.world.new_instance(), 0.6f);
  const int stations = static_cast<int>(l.path.points().size());
  const int segments = l.path.closed() ? stations : stations - 1;
  const double spacing = l.path.spacing(), thickness = 0.08;
  for (int i = 0; i < segments; ++i) {
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

// ---------------------------------------------------------------------------------------------
// Moving things.

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
      return {};
  }
  return {};
}

// Cars in other lanes at their own speeds. In the ego vehicle's lane only on an open synthetic
// path, ahead and faster or behind and slower, so that nothing drives through the ego vehicle.
void add_moving_cars(World& world, const Path& path, const ScenarioParams& p, double ego_start_s,
                     bool ego_lane_allowed, Rng& rng) {
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
        if (!ahead && car.motion.start_s > ego_start_s - 15.0) continue;
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

// ---------------------------------------------------------------------------------------------
// Scenario layouts.

void layout_urban(Layout& l) {
  for (double side : {-1.0, 1.0}) {
    add_parked_cars(l, side);
    add_street_furniture(l, side);
    add_street_trees(l, side);
    add_standing_people(l, side);
    add_buildings(l, side);
    add_front_gardens(l, side);
  }
}

void layout_highway(Layout& l) {
  const double w = l.p.road_half_width;
  add_guard_rail(l, -w - 0.3, -1.0);
  add_guard_rail(l, w + 0.3, 1.0);
  add_guard_rail(l, -0.35, 1.0);  // the median's two rails, back to back
  add_guard_rail(l, 0.35, -1.0);
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
      if (!l.placer.claim(centre, f.heading, Eigen::Vector2d(0.5 * length, 0.5 * depth), w + 1.0))
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
      if (!l.placer.claim(xy, 0.0, Eigen::Vector2d(0.3, 0.3), w + 1.0)) continue;
      const uint32_t surface =
          l.world.add_surface(SemanticClass::kPole, l.world.new_instance(), 0.3f);
      const Eigen::Vector3f base = l.at_ground(xy);
      add_power_pole(l.world.tile_at(base), base, f.left.cast<float>(), surface);
    }
  }
}

void make_prototypes(World& world, const ScenarioParams& p, Layout& layout, Rng& rng) {
  const uint32_t leaves = world.add_surface(SemanticClass::kVegetation, 0, 0.45f);
  const uint32_t wood = world.add_surface(SemanticClass::kTrunk, 0, 0.3f);
  const float jitter = static_cast<float>(p.leaf_jitter_m);
  for (int i = 0; i < kTreeShapes; ++i) {
    layout.tree_prototypes.push_back(static_cast<int>(world.plant_prototypes.size()));
    world.plant_prototypes.push_back(
        make_plant(random_tree_shape(rng), p.wind_states, jitter, leaves, wood, rng));
  }
  for (int i = 0; i < kBushShapes; ++i) {
    layout.bush_prototypes.push_back(static_cast<int>(world.plant_prototypes.size()));
    world.plant_prototypes.push_back(
        make_plant(random_bush_shape(rng), p.wind_states, jitter, leaves, wood, rng));
  }
  const uint32_t body = world.add_surface(SemanticClass::kMovingCar, 0, 0.5f);
  const uint32_t wheels = world.add_surface(SemanticClass::kMovingCar, 0, 0.1f);
  for (int i = 0; i < kCarShapes; ++i) {
    world.car_prototypes.emplace_back();
    add_car(world.car_prototypes.back(), Eigen::Isometry3f::Identity(), random_car_shape(i, rng),
            body, wheels);
  }
}

void check_request(const SceneRequest& r) {
  if (r.frames < 1)
    throw std::invalid_argument("frames = " + std::to_string(r.frames) + ": expected at least 1");
  if (!(r.frame_period > 0.0)) throw std::invalid_argument("frame period must be positive");
  if (r.scenario.wind_states < 1) throw std::invalid_argument("wind_states: expected at least 1");
  if (!(r.scenario.cruise_speed_mps > 0.0 && r.scenario.cruise_speed_mps <= 70.0))
    throw std::invalid_argument("speed = " + std::to_string(r.scenario.cruise_speed_mps) +
                                " m/s: expected (0, 70]");
  if (r.trajectory_poses.size() != r.trajectory_times.size())
    throw std::invalid_argument("trajectory: as many times as poses expected");
  if (!r.trajectory_poses.empty() &&
      static_cast<std::size_t>(r.frames) > r.trajectory_poses.size()) {
    throw std::invalid_argument("frames = " + std::to_string(r.frames) + " exceeds the " +
                                std::to_string(r.trajectory_poses.size()) +
                                " poses of the trajectory");
  }
}

// The path and the trajectory along a recorded trajectory. Returns the ego vehicle's start on
// the path.
double drive_recorded(const SceneRequest& request, const Shake& shake, GeneratedScene& scene) {
  const std::size_t count =
      std::min<std::size_t>(request.frames + 1, request.trajectory_poses.size());
  const std::vector<Eigen::Isometry3d> poses(request.trajectory_poses.begin(),
                                             request.trajectory_poses.begin() + count);
  const std::vector<double> times(request.trajectory_times.begin(),
                                  request.trajectory_times.begin() + count);
  const double lead = lead_length(request);
  scene.path = recorded_path(poses, request.sensor_height, request.scenario.ego_lateral, lead);
  scene.trajectory = std::make_shared<SampledTrajectory>(times, poses, shake);
  for (std::size_t i = 1; i < poses.size(); ++i)
    scene.drive_length_m += (poses[i].translation() - poses[i - 1].translation()).norm();
  return lead;
}

// The same along a synthetic path for the scenario.
double drive_synthetic(const SceneRequest& request, const HeightField& hills, const Shake& shake,
                       GeneratedScene& scene) {
  const ScenarioParams& p = request.scenario;
  Rng speed_rng(derive_seed(request.seed, kSpeedStream));
  SpeedProfile speed{p.cruise_speed_mps, p.speed_variation, 20.0,
                     speed_rng.uniform(0.0, 2.0 * M_PI)};
  const double sweep_end = request.frames * request.frame_period;
  const double lead = lead_length(request);
  double ego_start_s = lead;
  if (p.kind == ScenarioKind::kLoop) {
    const double lap = speed.distance(sweep_end);
    const std::vector<PathPiece> pieces = loop_pieces(std::max(kMinLoopLength, lap));
    scene.path = synthetic_path(pieces, true, hills);
    ego_start_s = 0.5 * pieces.front().length;  // halfway along the first straight
    // The sampled loop is a little shorter than its arcs: match the speed to it, so that the
    // requested frames end where they began.
    if (lap > kMinLoopLength) speed.cruise_mps *= scene.path->length() / lap;
  } else {
    Rng path_rng(derive_seed(request.seed, kPathStream));
    const double length = 2.0 * lead + speed.distance(sweep_end + request.frame_period);
    scene.path = synthetic_path(open_pieces(p.kind, length, lead, path_rng), false, hills);
  }
  scene.trajectory =
      std::make_shared<PathTrajectory>(scene.path, speed, ego_start_s, p.ego_lateral,
                                       request.sensor_height, shake, request.frame_period);
  scene.drive_length_m = speed.distance(sweep_end);
  return ego_start_s;
}

// Road, terrain, objects and moving things along the scene's path.
std::shared_ptr<World> populate(const SceneRequest& request, const GeneratedScene& scene,
                                const TerrainModel& terrain, double ego_start_s, bool recorded) {
  const ScenarioParams& p = request.scenario;
  const Path& path = *scene.path;
  auto world = std::make_shared<World>();
  world->seed = request.seed;
  world->path = scene.path;
  build_road(*world, path, road_cross_section(p));
  if (!p.tunnel) build_terrain(*world, path, terrain, request.reach);

  Rng plant_rng(derive_seed(request.seed, kPlantStream));
  Rng layout_rng(derive_seed(request.seed, kLayoutStream));
  Placer placer(path);
  Layout layout{*world, path, terrain, p, layout_rng, placer, {}, {}};
  make_prototypes(*world, p, layout, plant_rng);
  switch (p.kind) {
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
      layout_urban(layout);
      break;
    case ScenarioKind::kHighway:
      layout_highway(layout);
      break;
    case ScenarioKind::kVegetation:
      layout_vegetation(layout);
      break;
    case ScenarioKind::kTunnel:
      break;  // the walls are part of the road's cross-section
  }
  Rng mover_rng(derive_seed(request.seed, kMoverStream));
  add_moving_cars(*world, path, p, ego_start_s, !recorded && !path.closed(), mover_rng);
  add_walkers(*world, path, p, mover_rng);
  return world;
}

}  // namespace

GeneratedScene generate_scene(const SceneRequest& request) {
  check_request(request);
  const ScenarioParams& p = request.scenario;
  const bool recorded = !request.trajectory_poses.empty();
  Rng hill_rng(derive_seed(request.seed, kHillStream));
  const HeightField hills =
      recorded ? HeightField() : HeightField(hill_rng, p.hill_amplitude_m, p.hill_wavelength_m, 3);
  const HeightField relief(hill_rng, p.relief_amplitude_m, p.relief_wavelength_m, 4);
  const Shake shake =
      p.rough_road ? Shake(p.shake, derive_seed(request.seed, kShakeStream)) : Shake();

  GeneratedScene scene;
  const double ego_start_s = recorded ? drive_recorded(request, shake, scene)
                                      : drive_synthetic(request, hills, shake, scene);
  scene.path_length_m = scene.path->length();
  const TerrainModel terrain(*scene.path, p, hills, relief, !recorded, request.reach);
  scene.world = populate(request, scene, terrain, ego_start_s, recorded);
  return scene;
}

}  // namespace adaptive_lego_loam::sim
