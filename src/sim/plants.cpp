#include "adaptive_lego_loam/sim/plants.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_lego_loam::sim {
namespace {

// Trunks and limbs are prisms: a plant's scene then holds triangles only, which Embree traces
// faster than triangles and curves together. 12 sides: normals within 15 deg of a cylinder's.
constexpr int kWoodSides = 12;

struct Facet {
  Eigen::Vector3f centre;
  Eigen::Vector3f u, v;  // in-plane axes
};

Eigen::Vector3f random_unit_vector(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0), angle = rng.uniform(0.0, 2.0 * M_PI);
  const double r = std::sqrt(1.0 - z * z);
  return Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), z).cast<float>();
}

// A point of the unit ball; trees hold most leaves in the crown's outer shell.
Eigen::Vector3f random_point_in_ball(Rng& rng, bool favour_shell) {
  while (true) {
    const Eigen::Vector3d p(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double r = p.norm();
    if (r > 1.0) continue;
    if (favour_shell && r < 0.6 && !rng.chance(0.35)) continue;
    return p.cast<float>();
  }
}

Facet random_facet(const PlantShape& shape, Rng& rng) {
  const float half_height = 0.5f * shape.crown_height;
  const Eigen::Vector3f centre_of_crown(0.0f, 0.0f,
                                        (shape.tree ? shape.crown_base : 0.0f) + half_height);
  const Eigen::Vector3f unit = random_point_in_ball(rng, shape.tree);
  Facet facet;
  facet.centre =
      centre_of_crown + Eigen::Vector3f(shape.crown_radius * unit.x(),
                                        shape.crown_radius * unit.y(), half_height * unit.z());
  const Eigen::Vector3f normal = random_unit_vector(rng);
  facet.u = normal.unitOrthogonal();
  facet.v = normal.cross(facet.u);
  return facet;
}

void add_facet(GeometrySet& set, const Facet& facet, float side, uint32_t surface) {
  const float circumradius = side / std::sqrt(3.0f);
  Eigen::Vector3f corners[3];
  for (int k = 0; k < 3; ++k) {
    const float angle = 2.0f * static_cast<float>(M_PI) * k / 3.0f;
    corners[k] =
        facet.centre + circumradius * (std::cos(angle) * facet.u + std::sin(angle) * facet.v);
  }
  set.add_triangle(corners[0], corners[1], corners[2], surface);
}

// The facet as the wind leaves it in one state: moved by a few cm and turned a little.
Facet blown(const Facet& facet, float jitter, Rng& rng) {
  Facet moved = facet;
  moved.centre += Eigen::Vector3f(rng.normal(0.0, jitter), rng.normal(0.0, jitter),
                                  rng.normal(0.0, 0.5 * jitter));
  const Eigen::AngleAxisf turn(static_cast<float>(rng.normal(0.0, 0.25)), random_unit_vector(rng));
  moved.u = turn * facet.u;
  moved.v = turn * facet.v;
  return moved;
}

void add_wood(GeometrySet& set, const PlantShape& shape, uint32_t surface, Rng& rng) {
  const float top = shape.crown_base + 0.6f * shape.crown_height;
  set.add_prism(Eigen::Vector3f(0, 0, -0.3f), Eigen::Vector3f(0, 0, top), shape.trunk_radius,
                kWoodSides, surface);
  const int branches = rng.integer(3, 5);
  for (int i = 0; i < branches; ++i) {
    const float height =
        shape.crown_base + static_cast<float>(rng.uniform(0.1, 0.5)) * shape.crown_height;
    const float angle = static_cast<float>(rng.uniform(0.0, 2.0 * M_PI));
    const float reach = 0.6f * shape.crown_radius;
    set.add_prism(
        Eigen::Vector3f(0, 0, height),
        Eigen::Vector3f(reach * std::cos(angle), reach * std::sin(angle), height + 0.5f * reach),
        0.4f * shape.trunk_radius, kWoodSides, surface);
  }
}

}  // namespace

PlantShape random_tree_shape(Rng& rng) {
  PlantShape shape;
  shape.tree = true;
  shape.crown_radius = static_cast<float>(rng.uniform(1.8, 3.2));
  shape.crown_height = static_cast<float>(rng.uniform(3.0, 6.0));
  shape.crown_base = static_cast<float>(rng.uniform(2.2, 3.6));
  shape.trunk_radius = static_cast<float>(rng.uniform(0.12, 0.3));
  // As dense as KITTI's foliage: its returns move from one scan to the next as much as in
  // KITTI's scans (docs/simulator.md).
  shape.extinction = 11.2f;
  shape.max_facets = 40000;
  return shape;
}

PlantShape random_bush_shape(Rng& rng) {
  PlantShape shape;
  shape.tree = false;
  shape.crown_radius = static_cast<float>(rng.uniform(0.6, 1.6));
  shape.crown_height = static_cast<float>(rng.uniform(0.8, 2.2));
  shape.crown_base = 0.0f;
  shape.extinction = 22.4f;
  shape.max_facets = 24000;
  return shape;
}

PlantShape with_foliage_density(PlantShape shape, double density) {
  if (!(density > 0.0)) {
    throw std::invalid_argument("foliage density " + std::to_string(density) +
                                ": expected a positive multiple");
  }
  shape.extinction *= static_cast<float>(density);
  shape.max_facets = static_cast<int>(std::lround(shape.max_facets * density));
  return shape;
}

PlantPrototype make_plant(const PlantShape& shape, int wind_states, float leaf_jitter,
                          uint32_t leaf_surface, uint32_t wood_surface, Rng& rng) {
  const float volume = 4.0f / 3.0f * static_cast<float>(M_PI) * shape.crown_radius *
                       shape.crown_radius * 0.5f * shape.crown_height;
  // Randomly turned facets of area a at density n block a beam at a rate of n a / 2 per metre.
  const float preferred_area = shape.tree ? 0.03f : 0.012f;
  const int facets = std::clamp(static_cast<int>(2.0f * shape.extinction * volume / preferred_area),
                                50, shape.max_facets);
  const float area = 2.0f * shape.extinction * volume / facets;
  const float side = std::sqrt(4.0f * area / std::sqrt(3.0f));

  std::vector<Facet> rest;
  for (int i = 0; i < facets; ++i)
    rest.push_back(random_facet(shape, rng));
  GeometrySet wood;
  if (shape.tree) add_wood(wood, shape, wood_surface, rng);

  PlantPrototype prototype;
  prototype.radius = shape.crown_radius;
  for (int state = 0; state < wind_states; ++state) {
    GeometrySet set = wood;
    for (const Facet& facet : rest)
      add_facet(set, blown(facet, leaf_jitter, rng), side, leaf_surface);
    prototype.wind_states.push_back(std::move(set));
  }
  return prototype;
}

}  // namespace adaptive_lego_loam::sim
