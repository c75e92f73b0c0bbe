#pragma once
// Trees and bushes as volumes of many small leaf facets (and cylinders for trunk and branches),
// each in several wind states in which every facet has moved and turned a little.

#include "adaptive_lego_loam/sim/random.h"
#include "adaptive_lego_loam/sim/world.h"

namespace adaptive_lego_loam::sim {

struct PlantShape {
  bool tree = true;           // a trunk under a raised crown; else a bush from the ground up
  float crown_radius = 2.5f;  // horizontal semi-axis of the crown ellipsoid
  float crown_height = 4.0f;  // vertical extent of the crown
  float crown_base = 2.5f;    // height of the crown's bottom (trees)
  float trunk_radius = 0.15f;
  // Extinction coefficient of the foliage (1/m): how far a beam gets into it. Facet sizes are
  // chosen to give it with at most `max_facets` facets.
  float extinction = 11.2f;
  int max_facets = 40000;
};

PlantShape random_tree_shape(Rng& rng);
PlantShape random_bush_shape(Rng& rng);
// The shape with its extinction times `density` and room for as many more facets, so that its
// leaves keep their size: beams stop nearer the crown's surface.
PlantShape with_foliage_density(PlantShape shape, double density);

// `leaf_jitter`: standard deviation of each facet's displacement between wind states (m).
PlantPrototype make_plant(const PlantShape& shape, int wind_states, float leaf_jitter,
                          uint32_t leaf_surface, uint32_t wood_surface, Rng& rng);

}  // namespace adaptive_lego_loam::sim
