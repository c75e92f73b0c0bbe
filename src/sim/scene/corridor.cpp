#include "corridor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "adaptive_lego_loam/sim/random.h"

namespace adaptive_lego_loam::sim {
namespace {

constexpr uint64_t kCorridorStream = 0x434F5252ull;  // "CORR"

// An office building: a suspended ceiling 2.7 m up (2.6-3.0 m is usual), doors of 1.0 x 2.1 m
// (a 0.9 m leaf in its frame) set 0.15 m back from the wall's face, every 10 m along each wall.
constexpr double kCeiling = 2.7, kDoorWidth = 1.0, kDoorHeight = 2.1, kDoorRecess = 0.15;
constexpr double kDoorSpacing = 10.0;
// Floors, ceilings and walls in pieces of at most this length, so that each lies in one tile.
constexpr double kPiece = 5.0;
// A robot ramps its acceleration up and down over half a second, and takes the turn at 0.5 m/s
// on a curve eased in and out (tightest radius 0.8 m).
constexpr double kSpeedRamp = 0.5, kTurnSpeed = 0.5, kTurnRadius = 0.8;

struct Surfaces {
  uint32_t wall, floor;
};

// A wall from `start` along the unit `along` for `length` m, its face toward the corridor and
// `outward` (unit, horizontal) pointing away from it, floor to ceiling, with a door centred at
// each of `doors` (m along it).
void add_wall(World& world, const Eigen::Vector2d& start, const Eigen::Vector2d& along,
              const Eigen::Vector2d& outward, double length, const std::vector<double>& doors,
              const Surfaces& surfaces) {
  auto point = [&](double u, double depth, double z) -> Eigen::Vector3f {
    const Eigen::Vector2d xy = start + u * along + depth * outward;
    return Eigen::Vector3f(xy.x(), xy.y(), z);
  };
  auto face = [&](double u0, double u1, double depth, double z0, double z1, uint32_t surface) {
    for (double u = u0; u < u1 - 1e-9; u += kPiece) {
      const double v = std::min(u + kPiece, u1);
      world.tile_at(point(u, depth, z0))
          .add_quad(point(u, depth, z0), point(v, depth, z0), point(v, depth, z1),
                    point(u, depth, z1), surface);
    }
  };
  double from = 0.0;
  for (double centre : doors) {
    const double a = centre - 0.5 * kDoorWidth, b = centre + 0.5 * kDoorWidth;
    face(from, a, 0.0, 0.0, kCeiling, surfaces.wall);
    face(a, b, 0.0, kDoorHeight, kCeiling, surfaces.wall);
    const uint32_t door = world.add_surface(SemanticClass::kBuilding, world.new_instance(), 0.4f);
    face(a, b, kDoorRecess, 0.0, kDoorHeight, door);  // the leaf
    GeometrySet& set = world.tile_at(point(centre, 0.0, 0.0));
    for (double jamb : {a, b}) {
      set.add_quad(point(jamb, 0.0, 0.0), point(jamb, kDoorRecess, 0.0),
                   point(jamb, kDoorRecess, kDoorHeight), point(jamb, 0.0, kDoorHeight),
                   surfaces.wall);
    }
    set.add_quad(point(a, 0.0, kDoorHeight), point(b, 0.0, kDoorHeight),
                 point(b, kDoorRecess, kDoorHeight), point(a, kDoorRecess, kDoorHeight),
                 surfaces.wall);
    from = b;
  }
  face(from, length, 0.0, 0.0, kCeiling, surfaces.wall);
}

// Doors every 10 m from a random first one, at least 1 m from the wall's ends.
std::vector<double> door_positions(double length, Rng& rng) {
  std::vector<double> doors;
  const double margin = 0.5 * kDoorWidth + 1.0;
  for (double u = margin + rng.uniform(0.0, kDoorSpacing); u < length - margin; u += kDoorSpacing)
    doors.push_back(u);
  return doors;
}

// Floor and ceiling over the rectangle [x0, x1] x [y0, y1].
void add_floor_and_ceiling(World& world, double x0, double x1, double y0, double y1,
                           const Surfaces& surfaces) {
  for (double x = x0; x < x1 - 1e-9; x += kPiece) {
    for (double y = y0; y < y1 - 1e-9; y += kPiece) {
      const double xe = std::min(x + kPiece, x1), ye = std::min(y + kPiece, y1);
      const std::pair<double, uint32_t> layers[] = {{0.0, surfaces.floor},
                                                    {kCeiling, surfaces.wall}};
      for (const auto& [z, surface] : layers) {
        const float h = static_cast<float>(z);
        world.tile_at(Eigen::Vector3f(x, y, h))
            .add_quad(Eigen::Vector3f(x, y, h), Eigen::Vector3f(xe, y, h),
                      Eigen::Vector3f(xe, ye, h), Eigen::Vector3f(x, ye, h), surface);
      }
    }
  }
}

struct Drive {
  SpeedProfile speed;
  double turn_start = 0.0;  // arc length where the turn begins
};

// Stops 2-4 s into the drive, slows for the turn 2-4 s after pulling away, stops again 2-4 s
// after the turn; each stop lasts 2-4 s, every change at 0.5-1.0 m/s^2.
Drive plan_drive(const ScenarioParams& p, double turn_length, Rng& rng) {
  Drive drive;
  SpeedProfile& speed = drive.speed;
  speed = {p.cruise_speed_mps, p.speed_variation, 20.0, 0.0, {}};
  const double cruise = p.cruise_speed_mps;
  auto stop = [&](double at) {
    const double rate = rng.uniform(0.5, 1.0), standing = rng.uniform(2.0, 4.0);
    const SpeedChange down{at, -cruise, rate, kSpeedRamp};
    const SpeedChange up{down.end_time() + standing, cruise, rate, kSpeedRamp};
    speed.changes.push_back(down);
    speed.changes.push_back(up);
    return up.end_time();
  };
  const double moving = stop(rng.uniform(2.0, 4.0));
  const double turn_speed = std::min(kTurnSpeed, cruise);
  const SpeedChange slow{moving + rng.uniform(2.0, 4.0), turn_speed - cruise, rng.uniform(0.5, 1.0),
                         kSpeedRamp};
  if (slow.delta_mps < 0.0) speed.changes.push_back(slow);
  drive.turn_start = speed.distance(slow.end_time());
  const SpeedChange resume{speed.time_at_distance(drive.turn_start + turn_length, slow.end_time()),
                           cruise - turn_speed, rng.uniform(0.5, 1.0), kSpeedRamp};
  if (resume.delta_mps > 0.0) speed.changes.push_back(resume);
  stop(resume.end_time() + rng.uniform(2.0, 4.0));
  return drive;
}

}  // namespace

GeneratedScene generate_corridor(const SceneRequest& request, const Shake& shake) {
  if (!request.trajectory_poses.empty()) {
    throw std::invalid_argument(
        "corridor: drives its own path; a recorded trajectory (--trajectory) is not supported");
  }
  const ScenarioParams& p = request.scenario;
  Rng rng(derive_seed(request.scene(), kCorridorStream));
  const double r = p.road_half_width, side = rng.sign();
  const std::vector<PathPiece> turn =
      eased_curve(side / kTurnRadius, 0.0, 0.5 * M_PI * kTurnRadius, 4);
  double turn_length = 0.0;
  for (const PathPiece& piece : turn)
    turn_length += piece.length;
  const Drive drive = plan_drive(p, turn_length, rng);
  const double sweep_end = request.frames * request.frame_period;
  const double beyond_turn =
      std::max(rng.uniform(30.0, 60.0), drive.speed.distance(sweep_end + request.frame_period) -
                                            drive.turn_start - turn_length + 10.0);
  const double behind = rng.uniform(3.0, 8.0);

  GeneratedScene scene;
  std::vector<PathPiece> pieces{{drive.turn_start, 0.0}};
  pieces.insert(pieces.end(), turn.begin(), turn.end());
  // Where the turn ends: the second corridor's centreline.
  const Eigen::Vector3d turned = trace_pieces(pieces, 0.05).back();
  pieces.push_back({beyond_turn, 0.0});
  scene.path = std::make_shared<Path>(trace_pieces(pieces, 0.05), false, 0.05);
  scene.trajectory = std::make_shared<PathTrajectory>(
      scene.path, drive.speed, 0.0, 0.0, request.height(), shake, request.frame_period);
  scene.path_length_m = scene.path->length();
  scene.drive_length_m = drive.speed.distance(sweep_end);
  scene.speed_changes = drive.speed.changes;

  auto world = std::make_shared<World>();
  world->seed = request.seed;
  world->path = scene.path;
  const uint16_t building = world->new_instance();
  const Surfaces surfaces{world->add_surface(SemanticClass::kBuilding, building, 0.7f),
                          world->add_surface(SemanticClass::kOtherGround, 0, 0.3f)};
  // Turning left (side +1) the second corridor runs along +y from the first one's end; turning
  // right, everything is mirrored in y.
  const double x0 = turned.x() - r, w = 2.0 * r;
  const double end = side * turned.y() + beyond_turn + 1.0;
  auto xy = [side](double x, double y) { return Eigen::Vector2d(x, side * y); };
  const Eigen::Vector2d ex(1.0, 0.0), ey = xy(0.0, 1.0);
  const std::vector<double> none;
  // back wall, the first corridor's two walls, the outer wall, the far end, the inner wall
  add_wall(*world, xy(-behind, -r), ey, -ex, w, none, surfaces);
  const double first = behind + x0 + w;
  add_wall(*world, xy(-behind, -r), ex, -ey, first, door_positions(first, rng), surfaces);
  add_wall(*world, xy(-behind, r), ex, ey, behind + x0, door_positions(behind + x0, rng), surfaces);
  add_wall(*world, xy(x0 + w, -r), ey, ex, end + r, door_positions(end + r, rng), surfaces);
  add_wall(*world, xy(x0, end), ex, ey, w, none, surfaces);
  add_wall(*world, xy(x0, r), ey, -ex, end - r, door_positions(end - r, rng), surfaces);
  const Eigen::Vector2d a = xy(-behind, -r), b = xy(x0 + w, r);
  add_floor_and_ceiling(*world, a.x(), b.x(), std::min(a.y(), b.y()), std::max(a.y(), b.y()),
                        surfaces);
  const Eigen::Vector2d c = xy(x0, r), d = xy(x0 + w, end);
  add_floor_and_ceiling(*world, c.x(), d.x(), std::min(c.y(), d.y()), std::max(c.y(), d.y()),
                        surfaces);
  scene.world = world;
  return scene;
}

}  // namespace adaptive_lego_loam::sim
