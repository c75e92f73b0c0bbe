#pragma once
// Part of the scene generator (scene_generator.cpp): placing objects without overlaps and off the
// road.

#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "adaptive_lego_loam/sim/objects.h"
#include "adaptive_lego_loam/sim/plants.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/terrain.h"

namespace adaptive_lego_loam::sim {

// The car shapes every scene has (World::car_prototypes).
constexpr int kCarShapes = 3;

class Placer {
 public:
  explicit Placer(const Path& path) : path_(path) {}

  // Takes an oriented rectangle of the ground when it overlaps nothing taken before nor ground
  // reserved for another owner, and every part of it keeps `road_clearance` from the centreline
  // of `road` (default: the path; 0: no such check).
  bool claim(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half,
             double road_clearance, const Path* road = nullptr, int owner = 0);

  // Keeps a rectangle for `owner` (a side street's own layout): others cannot claim it.
  void reserve(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& half, int owner) {
    for (int64_t key : cells_of(centre, yaw, half))
      reserved_.emplace(key, owner);
  }

 private:
  static constexpr double kCell = 0.5;

  std::vector<int64_t> cells_of(const Eigen::Vector2d& centre, double yaw,
                                const Eigen::Vector2d& half) const;

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
  double ground(const Eigen::Vector2d& xy) const;

  Eigen::Vector3f at_ground(const Eigen::Vector2d& xy) const {
    return Eigen::Vector3f(xy.x(), xy.y(), ground(xy));
  }

  // The next arc length of a sequence with `per_100m` items on average.
  double step(double per_100m) { return 100.0 / per_100m * rng.uniform(0.4, 1.6); }

  void add_plant(const std::vector<int>& prototypes, const Eigen::Vector2d& xy, double footprint,
                 double road_clearance);
};

}  // namespace adaptive_lego_loam::sim
