// Builds a scenario's World along a synthetic path or a recorded trajectory, from the seed alone.

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
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
  kRoadsideStream,
  kJunctionStream,
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

  // Takes an oriented rectangle of the ground when it overlaps nothing taken before nor ground
  // reserved for another owner, and every part of it keeps `road_clearance` from the centreline
  // of `road` (default: the path; 0: no such check).
  bool claim(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half,
             double road_clearance, const Path* road = nullptr, int owner = 0) {
    if (road_clearance > 0.0) {
      const Eigen::Vector2d ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
      const int nx = static_cast<int>(std::ceil(2.0 * half.x())) + 1;
      const int ny = static_cast<int>(std::ceil(2.0 * half.y())) + 1;
      Path::Nearest unused;
      for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
          const Eigen::Vector2d p = centre + (-half.x() + 2.0 * half.x() * i / (nx - 1)) * ex +
                                    (-half.y() + 2.0 * half.y() * j / (ny - 1)) * ey;
          if ((road ? *road : path_).nearest(p, road_clearance, unused)) return false;
        }
      }
    }
    const std::vector<int64_t> cells = cells_of(centre, yaw, half);
    for (int64_t key : cells) {
      if (taken_.count(key)) return false;
      const auto reserved = reserved_.find(key);
      if (reserved != reserved_.end() && reserved->second != owner) return false;
    }
    taken_.insert(cells.begin(), cells.end());
    return true;
  }

  // Keeps a rectangle for `owner` (a side street's own layout): others cannot claim it.
  void reserve(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half, int owner) {
    for (int64_t key : cells_of(centre, yaw, half))
      reserved_.emplace(key, owner);
  }

 private:
  static constexpr double kCell = 0.5;

  std::vector<int64_t> cells_of(const Eigen::Vector2d& centre, double yaw,
                                const Eigen::Vector2d& half) const {
    const Eigen::Vector2d ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
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
        cells.push_back((static_cast<int64_t>(x) << 32) ^ (static_cast<int64_t>(y) & 0xFFFFFFFFll));
      }
    }
    return cells;
  }

  const Path& path_;
  std::unordered_set<int64_t> taken_;
  std::unordered_map<int64_t, int> reserved_;
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
  double start = 0.0;  // objects along the street from here (side streets: past the corner)
  int owner = 0;       // of the ground it may claim (Placer::reserve)

  double length() const { return path.length(); }

  // Placer::claim with the clearance kept from this layout's street.
  bool claim(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half,
             double road_clearance) {
    return placer.claim(centre, yaw, half, road_clearance, &path, owner);
  }

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
    if (!claim(xy, 0.0, Eigen::Vector2d::Constant(footprint), road_clearance)) return;
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

// Houses and blocks along one side of the street. Houses (`house_share` of the lots) are small,
// set back behind front gardens, a little askew and spaced out, so that their side walls show;
// blocks are long, close to the sidewalk and mostly joined.
void add_buildings(Layout& l, double side) {
  const ScenarioParams& p = l.p;
  const double clearance = p.road_half_width + p.sidewalk_width + 0.3;
  for (double s = l.start + l.rng.uniform(0.0, 10.0); s < l.length();) {
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

// Street lights (and some traffic signs) at the edge of the road.
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

// Bushes and hedges in the strip between the sidewalk and the buildings.
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

// Sweeps a cross-section along the path over [s0, s1]: `outline` holds (offset to the left of
// `lateral`, height) points, joined in order (close it by repeating the first). Heights are above
// the road's centreline, or above the ground under `lateral` when `on_ground`.
void sweep_outline(Layout& l, double s0, double s1, double lateral,
                   const std::vector<Eigen::Vector2d>& outline, bool on_ground, uint32_t surface,
                   bool capped = false) {
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

// A guard rail along [s0, s1] of the path `lateral` m left of the centreline; its posts stand on
// the side `outward` (+1: left) of the rail, behind it as seen from the road.
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

// A highway is built in stretches of a few hundred metres, each with its median (double guard
// rail or concrete barrier) and, on each side, a guard rail in front of open verges and fields,
// a noise wall, an earth berm or the slope of a cutting.
enum class Roadside { kOpen, kNoiseWall, kBerm, kCutting };

struct HighwayStretch {
  double s0 = 0.0, s1 = 0.0;
  bool concrete_median = false;
  Roadside roadside[2] = {Roadside::kOpen, Roadside::kOpen};  // [0] right, [1] left
  double height[2] = {0.0, 0.0};                              // of the noise wall or berm
};

constexpr double kNoiseWallOffset = 2.5;  // behind the road's edge
constexpr double kBermToeOffset = 6.0;    // past the ditch

std::vector<HighwayStretch> plan_highway(const Path& path, Rng& rng) {
  std::vector<HighwayStretch> stretches;
  for (double s = 0.0; s < path.length();) {
    HighwayStretch stretch;
    stretch.s0 = s;
    stretch.s1 = std::min(path.length(), s + rng.uniform(250.0, 700.0));
    stretch.concrete_median = rng.chance(0.6);
    for (int side = 0; side < 2; ++side) {
      const double draw = rng.uniform();
      stretch.roadside[side] = draw < 0.5    ? Roadside::kOpen
                               : draw < 0.65 ? Roadside::kNoiseWall
                               : draw < 0.8  ? Roadside::kBerm
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

// Side streets branching off the path at junctions, on straight stretches, at 60-140 m, to one
// side or both, a little askew; none crosses the path elsewhere or another side street. On a
// closed path (a loop, counter-clockwise) only to the outside.
std::vector<SideStreet> plan_junctions(const Path& path, const ScenarioParams& p,
                                       const TerrainModel& terrain, Rng& rng) {
  std::vector<SideStreet> streets;
  if (p.junctions_per_km <= 0.0) return streets;
  const double w = p.road_half_width, mean_gap = 1000.0 / p.junctions_per_km;
  auto heading_change = [&](double s0, double s1) {
    return std::abs(std::remainder(path.at(s1).heading - path.at(s0).heading, 2.0 * M_PI));
  };
  for (double s = rng.uniform(0.3, 1.0) * mean_gap; s < path.length();
       s += mean_gap * rng.uniform(0.6, 1.4)) {
    if (heading_change(s - 25.0, s + 25.0) > 5.0 * M_PI / 180.0) continue;  // on a bend
    const double draw = rng.uniform();
    std::vector<double> sides =
        draw < 0.4 ? std::vector<double>{-1.0, 1.0} : std::vector<double>{draw < 0.7 ? -1.0 : 1.0};
    for (double side : sides) {
      if (path.closed() && side > 0.0) continue;
      SideStreet street;
      street.corner = p.sidewalk_width;
      const double skew = std::clamp(rng.normal(0.0, 0.14), -0.35, 0.35);
      double length = rng.uniform(60.0, 120.0);
      const Path::Frame f = path.at(s);
      const Eigen::Vector2d start = (f.position + side * w * f.left).head<2>();
      const Eigen::Vector2d out = Eigen::Rotation2Dd(skew) * (side * f.left.head<2>()).normalized();
      // Shorten it before it comes near another stretch of the path or another side street.
      for (double t = 12.0; t <= length + 10.0; t += 2.0) {
        const Eigen::Vector2d xy = start + t * out;
        Path::Nearest unused;
        bool blocked = path.nearest(xy, w + p.sidewalk_width + street.outer() + 3.0, unused);
        for (const SideStreet& other : streets)
          blocked |= other.path->nearest(xy, 2.0 * street.outer() + 3.0, unused);
        if (blocked) {
          length = t - 12.0;
          break;
        }
      }
      if (length < 30.0) continue;
      std::vector<Eigen::Vector3d> points;
      for (double t = 0.0; t <= length + 1e-9; t += 1.0) {
        const Eigen::Vector2d xy = start + t * out;
        // From the path's height at the junction into the lie of the land.
        const double blend = std::clamp((t - 3.0) / 17.0, 0.0, 1.0);
        const double z = (1.0 - blend) * f.position.z() + blend * terrain.reference(xy);
        points.emplace_back(xy.x(), xy.y(), z);
      }
      street.path = std::make_shared<Path>(points, false);
      streets.push_back(street);
    }
  }
  return streets;
}

// What lines the road, decided before the terrain is built: the terrain follows berms and side
// streets.
struct RoadPlan {
  std::vector<HighwayStretch> highway;
  std::vector<SideStreet> side_streets;
};

RoadPlan plan_road(const SceneRequest& request, const Path& path, TerrainModel& terrain) {
  const ScenarioParams& p = request.scenario;
  RoadPlan plan;
  if (p.kind == ScenarioKind::kHighway) {
    Rng rng(derive_seed(request.seed, kRoadsideStream));
    plan.highway = plan_highway(path, rng);
    terrain.add_berms(highway_berms(plan.highway, p.road_half_width));
  }
  if (p.kind == ScenarioKind::kUrban || p.kind == ScenarioKind::kLoop) {
    Rng rng(derive_seed(request.seed, kJunctionStream));
    plan.side_streets = plan_junctions(path, p, terrain, rng);
    terrain.add_side_streets(plan.side_streets);
  }
  return plan;
}

// Road, terrain, objects and moving things along the scene's path.
std::shared_ptr<World> populate(const SceneRequest& request, const GeneratedScene& scene,
                                const TerrainModel& terrain, const RoadPlan& plan,
                                double ego_start_s, bool recorded) {
  const ScenarioParams& p = request.scenario;
  const Path& path = *scene.path;
  auto world = std::make_shared<World>();
  world->seed = request.seed;
  world->path = scene.path;
  build_road(*world, path, road_cross_section(p), plan.side_streets);
  for (const SideStreet& street : plan.side_streets)
    build_road(*world, *street.path, side_street_cross_section(street), {}, street.corner);
  if (!p.tunnel) build_terrain(*world, path, terrain, request.reach);

  Rng plant_rng(derive_seed(request.seed, kPlantStream));
  Rng layout_rng(derive_seed(request.seed, kLayoutStream));
  Placer placer(path);
  Layout layout{*world, path, terrain, p, layout_rng, placer, {}, {}};
  make_prototypes(*world, p, layout, plant_rng);
  switch (p.kind) {
    case ScenarioKind::kUrban:
    case ScenarioKind::kLoop:
      layout_urban(layout, plan.side_streets);
      break;
    case ScenarioKind::kHighway:
      layout_highway(layout, plan.highway);
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
  TerrainModel terrain(*scene.path, p, hills, relief, !recorded, request.reach);
  const RoadPlan plan = plan_road(request, *scene.path, terrain);
  scene.world = populate(request, scene, terrain, plan, ego_start_s, recorded);
  return scene;
}

}  // namespace adaptive_lego_loam::sim
