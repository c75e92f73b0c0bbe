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
#include "scene/corridor.h"
#include "scene/layouts.h"
#include "scene/paths.h"
#include "scene/placement.h"
#include "scene/traffic.h"
#include "scene/tunnel.h"

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
  kTunnelStream,
};

constexpr int kTreeShapes = 4, kBushShapes = 4;
constexpr double kMinLoopLength = 160.0;

double lead_length(const SceneRequest& request) {
  return request.reach + 40.0;
}

void make_prototypes(World& world, const ScenarioParams& p, Layout& layout, Rng& rng) {
  const uint32_t leaves = world.add_surface(SemanticClass::kVegetation, 0, 0.45f);
  const uint32_t wood = world.add_surface(SemanticClass::kTrunk, 0, 0.3f);
  const float jitter = static_cast<float>(p.leaf_jitter_m);
  for (int i = 0; i < kTreeShapes; ++i) {
    layout.tree_prototypes.push_back(static_cast<int>(world.plant_prototypes.size()));
    world.plant_prototypes.push_back(
        make_plant(with_foliage_density(random_tree_shape(rng), p.foliage_density), p.wind_states,
                   jitter, leaves, wood, rng));
  }
  for (int i = 0; i < kBushShapes; ++i) {
    layout.bush_prototypes.push_back(static_cast<int>(world.plant_prototypes.size()));
    world.plant_prototypes.push_back(
        make_plant(with_foliage_density(random_bush_shape(rng), p.foliage_density), p.wind_states,
                   jitter, leaves, wood, rng));
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
  if (r.laps < 1)
    throw std::invalid_argument("laps = " + std::to_string(r.laps) + ": expected at least 1");
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
  scene.path = recorded_path(poses, request.height(), request.scenario.ego_lateral, lead);
  scene.trajectory = std::make_shared<SampledTrajectory>(times, poses, shake);
  for (std::size_t i = 1; i < poses.size(); ++i)
    scene.drive_length_m += (poses[i].translation() - poses[i - 1].translation()).norm();
  return lead;
}

// The same along a synthetic path for the scenario.
double drive_synthetic(const SceneRequest& request, const HeightField& hills, const Shake& shake,
                       const std::optional<TunnelPlan>& tunnel, GeneratedScene& scene) {
  const ScenarioParams& p = request.scenario;
  Rng speed_rng(derive_seed(request.scene(), kSpeedStream));
  SpeedProfile speed{
      p.cruise_speed_mps, p.speed_variation, 20.0, speed_rng.uniform(0.0, 2.0 * M_PI), {}};
  const double sweep_end = request.frames * request.frame_period;
  const double lead = lead_length(request);
  double ego_start_s = lead;
  if (p.kind == ScenarioKind::kLoop) {
    const double lap = speed.distance(sweep_end) / request.laps;
    const std::vector<PathPiece> pieces = loop_pieces(std::max(kMinLoopLength, lap));
    scene.path = synthetic_path(pieces, true, hills);
    ego_start_s = 0.5 * pieces.front().length;  // halfway along the first straight
    // The sampled loop is a little shorter than its arcs: match the speed to it, so that the
    // requested frames end where they began.
    if (lap > kMinLoopLength) speed.cruise_mps *= scene.path->length() / lap;
  } else {
    if (tunnel) {
      Rng tunnel_rng(derive_seed(request.scene(), kTunnelStream, 1));
      speed.changes = tunnel_speed_changes(p, speed, tunnel->portal_s - ego_start_s, tunnel_rng);
    }
    Rng path_rng(derive_seed(request.scene(), kPathStream));
    const double length = 2.0 * lead + speed.distance(sweep_end + request.frame_period);
    scene.path = synthetic_path(
        tunnel ? tunnel_pieces(*tunnel, length) : open_pieces(p.kind, length, lead, path_rng),
        false, hills);
  }
  scene.trajectory = std::make_shared<PathTrajectory>(
      scene.path, speed, ego_start_s, p.ego_lateral, request.height(), shake, request.frame_period);
  scene.drive_length_m = speed.distance(sweep_end);
  scene.speed_changes = speed.changes;
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

RoadPlan plan_road(const SceneRequest& request, const Path& path,
                   const std::optional<TunnelPlan>& tunnel, TerrainModel& terrain) {
  const ScenarioParams& p = request.scenario;
  RoadPlan plan;
  if (tunnel) terrain.add_berms(tunnel_cutting(p, *tunnel, path.length()));
  if (p.kind == ScenarioKind::kHighway) {
    Rng rng(derive_seed(request.scene(), kRoadsideStream));
    plan.highway = plan_highway(request.scenario, path, rng);
    terrain.add_berms(highway_berms(plan.highway, p.road_half_width));
  }
  if (p.kind == ScenarioKind::kUrban || p.kind == ScenarioKind::kLoop) {
    Rng rng(derive_seed(request.scene(), kJunctionStream));
    plan.side_streets = plan_junctions(path, p, terrain, rng);
    terrain.add_side_streets(plan.side_streets);
  }
  return plan;
}

// Road, terrain, objects and moving things along the scene's path.
std::shared_ptr<World> populate(const SceneRequest& request, const GeneratedScene& scene,
                                const TerrainModel& terrain, const RoadPlan& plan,
                                const std::optional<TunnelPlan>& tunnel, double ego_start_s,
                                bool recorded) {
  const ScenarioParams& p = request.scenario;
  const Path& path = *scene.path;
  auto world = std::make_shared<World>();
  world->seed = request.seed;
  world->path = scene.path;
  if (tunnel) {
    // Open road up to the portal, the tunnel's ledges from there on; terrain along the approach.
    build_road(*world, path, tunnel_road_section(p), {}, tunnel->portal_s);
    build_terrain(*world, *tunnel_approach(path, *tunnel), terrain, request.reach);
  } else {
    build_road(*world, path, road_cross_section(p), plan.side_streets);
  }
  for (const SideStreet& street : plan.side_streets)
    build_road(*world, *street.path, side_street_cross_section(street), {}, street.corner);
  if (!p.tunnel) build_terrain(*world, path, terrain, request.reach);

  Rng plant_rng(derive_seed(request.scene(), kPlantStream));
  Rng layout_rng(derive_seed(request.scene(), kLayoutStream));
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
      layout_tunnel(layout, *tunnel);
      break;
    case ScenarioKind::kCorridor:
      break;  // generate_corridor builds it
  }
  Rng mover_rng(derive_seed(request.seed, kMoverStream));
  add_moving_cars(*world, path, p, ego_start_s, !recorded && !path.closed(),
                  !scene.speed_changes.empty(), mover_rng);
  add_walkers(*world, path, p, mover_rng);
  return world;
}

// The scene's drive joined smoothly: its trajectory becomes the smooth one.
GeneratedScene join_smoothly(GeneratedScene scene, const SceneRequest& request, bool recorded) {
  scene.motion = std::make_shared<const SmoothTrajectory>(scene.trajectory, request.frames,
                                                          recorded ? kRecordedCutoffHz : 0.0);
  scene.trajectory = scene.motion;
  return scene;
}

}  // namespace

GeneratedScene generate_scene(const SceneRequest& request) {
  check_request(request);
  const ScenarioParams& p = request.scenario;
  const bool recorded = !request.trajectory_poses.empty();
  const Shake shake =
      p.rough_road ? Shake(p.shake, derive_seed(request.seed, kShakeStream)) : Shake();
  if (p.kind == ScenarioKind::kCorridor)
    return join_smoothly(generate_corridor(request, shake), request, false);
  Rng hill_rng(derive_seed(request.scene(), kHillStream));
  const HeightField hills =
      recorded ? HeightField() : HeightField(hill_rng, p.hill_amplitude_m, p.hill_wavelength_m, 3);
  const HeightField relief(hill_rng, p.relief_amplitude_m, p.relief_wavelength_m, 4);
  std::optional<TunnelPlan> tunnel;
  if (p.kind == ScenarioKind::kTunnel) {
    Rng tunnel_rng(derive_seed(request.scene(), kTunnelStream));
    tunnel = plan_tunnel(p, lead_length(request), tunnel_rng);
  }

  GeneratedScene scene;
  const double ego_start_s = recorded ? drive_recorded(request, shake, scene)
                                      : drive_synthetic(request, hills, shake, tunnel, scene);
  scene.path_length_m = scene.path->length();
  if (tunnel) scene.tunnel_entry_m = tunnel->portal_s - ego_start_s;
  TerrainModel terrain(*scene.path, p, hills, relief, !recorded, request.reach);
  const RoadPlan plan = plan_road(request, *scene.path, tunnel, terrain);
  scene.world = populate(request, scene, terrain, plan, tunnel, ego_start_s, recorded);
  return join_smoothly(std::move(scene), request, recorded);
}

}  // namespace adaptive_lego_loam::sim
