#pragma once
// Everything a scene holds, as plain data: static geometry in square tiles, plants (instances of
// leaf-facet prototypes in several wind states), cars and people moving along the path.

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "adaptive_lego_loam/sim/geometry.h"
#include "adaptive_lego_loam/sim/path.h"

namespace adaptive_lego_loam::sim {

using TileKey = std::pair<int, int>;

// A plant's shape in several wind states: the same leaf facets, each moved by a few centimetres
// differently in every state. Each frame shows every plant in one state drawn at random, so
// foliage returns are not repeatable from scan to scan.
struct PlantPrototype {
  std::vector<GeometrySet> wind_states;  // local frame, base of the plant at the origin
  float radius = 1.0f;                   // horizontal reach from the base
};

struct Plant {
  int prototype = 0;
  Eigen::Vector3f base = Eigen::Vector3f::Zero();
  float yaw = 0.0f;
  float scale = 1.0f;
  uint16_t instance = 0;
  float sway_phase = 0.0f;
};

// Moving along the world's path: at time t at arc length s0 + speed * t (speed < 0: against the
// path's direction), `lateral` metres to its left.
struct PathMotion {
  double start_s = 0.0;
  double speed = 0.0;
  double lateral = 0.0;
};

struct MovingCar {
  int prototype = 0;  // index into World::car_prototypes
  PathMotion motion;
  uint16_t instance = 0;
};

struct Walker {
  PathMotion motion;
  float height = 1.75f;
  float gait_phase = 0.0f;
  uint16_t instance = 0;
  uint32_t surface = 0;
};

struct WindParams {
  float sway_deg = 0.6f;  // whole-plant sway amplitude
  float sway_hz = 0.4f;
};

struct World {
  float tile_size = 64.0f;
  uint64_t seed = 0;  // drives the per-frame wind state of each plant
  std::vector<Surface> surfaces;
  std::map<TileKey, GeometrySet> tiles;  // static geometry in world coordinates
  std::vector<PlantPrototype> plant_prototypes;
  std::vector<Plant> plants;
  std::vector<GeometrySet> car_prototypes;  // local frame: x forward, bottom at z = 0
  std::vector<MovingCar> moving_cars;
  std::vector<Walker> walkers;
  std::shared_ptr<const Path> path;  // needed when there are moving cars or walkers
  WindParams wind;

  uint32_t add_surface(SemanticClass semantic, uint16_t instance, float reflectivity);
  // A fresh instance id; throws std::runtime_error past 65535 (SemanticKITTI's 16 bits).
  uint16_t new_instance();
  TileKey tile_of(const Eigen::Vector3f& point) const;
  GeometrySet& tile_at(const Eigen::Vector3f& point) { return tiles[tile_of(point)]; }

 private:
  uint32_t next_instance_ = 1;
};

// Where a path-following object is at `time`: on the road surface, x along its direction of travel.
Eigen::Isometry3d path_motion_pose(const Path& path, const PathMotion& motion, double time);

// A walking person in its own frame (x forward, feet at z = 0) is one of kWalkerPoses poses of a
// gait cycle, in which legs and arms swing, of a person kWalkerHeight tall scaled to its height.
constexpr int kWalkerPoses = 16;
constexpr float kWalkerHeight = 1.75f;
// The pose of the walker's gait at `time`, in [0, kWalkerPoses).
int walker_pose(const Walker& walker, double time);
GeometrySet walker_pose_geometry(int pose, uint32_t surface);

}  // namespace adaptive_lego_loam::sim
