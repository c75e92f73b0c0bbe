#pragma once
// The ground of a scene: hills, the road's cross-section swept along the path (road, curbs,
// sidewalks, lane markings, tunnel walls), and terrain tiles that meet the road's edges.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/sim/path.h"
#include "adaptive_lego_loam/sim/random.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/world.h"

namespace adaptive_lego_loam::sim {

// A sum of plane waves: smooth hills or small relief.
class HeightField {
 public:
  HeightField() = default;
  // `count` waves of random direction and phase, wavelengths within a factor of two of
  // `wavelength`; their amplitudes add up to `amplitude`.
  HeightField(Rng& rng, double amplitude, double wavelength, int count);
  double at(const Eigen::Vector2d& xy) const;

 private:
  struct Wave {
    Eigen::Vector2d wave_vector;
    double amplitude, phase;
  };
  std::vector<Wave> waves_;
};

// One straight piece of the road's cross-section, from (d0, z0) to (d1, z1): d left of the
// centreline, z above it. Swept along the path it becomes a strip of quads.
struct CrossSectionPiece {
  double d0, z0, d1, z1;
  SemanticClass semantic;
  float reflectivity;
  double dash_on = 0.0, dash_period = 0.0;  // > 0: only the first dash_on m of every period
};

std::vector<CrossSectionPiece> road_cross_section(const ScenarioParams& scenario);

// An earth bank beside the road (a noise-protection berm) over [s0, s1] of the path: its foot
// `toe` m from the centreline on side `side` (+1: left), `height` m high with 1:1.5 slopes and a
// `crest` m wide top; it rises and falls over `ramp` m at its ends.
struct Berm {
  double s0 = 0.0, s1 = 0.0;
  double side = 1.0;
  double toe = 0.0;
  double height = 3.0;
  double crest = 1.5;
  double ramp = 25.0;
};

// A street branching off the path at a junction: its centreline starts at the edge of the path's
// carriageway and runs away from it, with heights from the road there into the terrain.
struct SideStreet {
  std::shared_ptr<const Path> path;
  double half_width = 4.0;  // carriageway
  double sidewalk_width = 2.5;
  double curb_height = 0.12;
  double corner =
      3.0;  // its sidewalks start here: before, the path's own sidewalk turns the corner
  double outer() const { return half_width + sidewalk_width; }
};

std::vector<CrossSectionPiece> side_street_cross_section(const SideStreet& street);

// Ground height anywhere: the road's profile near the path, blending into hills and relief.
class TerrainModel {
 public:
  // With `path_follows_hills` the path's heights were taken from `hills`, which then give the
  // ground far from the road; otherwise (a recorded trajectory) the height of the nearest road
  // does, on a 16 m grid covering everything within `reach` of the path.
  TerrainModel(const Path& path, const ScenarioParams& scenario, HeightField hills,
               HeightField relief, bool path_follows_hills, double reach);
  // Berms and side streets shape the ground around them; add them before building the terrain.
  void add_berms(const std::vector<Berm>& berms) { berms_ = berms; }
  void add_side_streets(const std::vector<SideStreet>& streets) { side_streets_ = streets; }
  const std::vector<SideStreet>& side_streets() const { return side_streets_; }
  // `covered` is set when the point lies under the road or a sidewalk.
  double height(const Eigen::Vector2d& xy, bool* covered = nullptr) const;
  // The smooth ground height (hills, or the road's height spread around) without the relief.
  double reference(const Eigen::Vector2d& xy) const;
  // False when nothing within `radius` of `centre` is near enough to the road to be shaped by it.
  bool near_road(const Eigen::Vector2d& centre, double radius) const;
  // Height away from the road: hills and relief only.
  double far_height(const Eigen::Vector2d& xy) const { return reference(xy) + relief_.at(xy); }

 private:
  double profile(double distance) const;
  double berm_height(const Path::Nearest& nearest) const;

  const Path& path_;
  HeightField hills_, relief_;
  bool path_follows_hills_;
  std::vector<std::pair<double, double>> profile_;  // (distance from centreline, height)
  // Road heights spread over a coarse grid (recorded trajectories only).
  Eigen::Vector2d grid_origin_ = Eigen::Vector2d::Zero();
  int grid_columns_ = 0, grid_rows_ = 0;
  std::vector<double> grid_heights_;
  double covered_until_ = 0.0, blend_start_ = 0.0, blend_end_ = 0.0;
  std::vector<Berm> berms_;
  std::vector<SideStreet> side_streets_;
};

// Sweeps the cross-section along the path into the world's tiles; pieces off the carriageway are
// left out where they would cross another stretch of the same road or a side street's
// carriageway, and from [0, skip_start_off_carriageway) of the path.
void build_road(World& world, const Path& path, const std::vector<CrossSectionPiece>& section,
                const std::vector<SideStreet>& side_streets = {},
                double skip_start_off_carriageway = 0.0);

// Terrain tiles (1 m grid) covering everything within `reach` of the path.
void build_terrain(World& world, const Path& path, const TerrainModel& terrain, double reach);

// True when xy lies on the road (within `half_width` of the centreline) at an arc length far from
// `s`: another stretch of the same road, such as a crossing.
bool on_other_stretch(const Path& path, const Eigen::Vector2d& xy, double s, double half_width);

}  // namespace adaptive_lego_loam::sim
