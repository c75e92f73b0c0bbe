#pragma once
// Part of the scene generator (scene_generator.cpp): objects common to several scenarios.

#include <Eigen/Core>
#include <vector>

#include "placement.h"

namespace adaptive_lego_loam::sim {

// Houses and blocks along one side of the street. Houses (`house_share` of the lots) are small,
// set back behind front gardens, a little askew and spaced out, so that their side walls show;
// blocks are long, close to the sidewalk and mostly joined.
void add_buildings(Layout& l, double side);

// Street lights (and some traffic signs) at the edge of the road.
void add_street_furniture(Layout& l, double side);

void add_parked_cars(Layout& l, double side);

void add_street_trees(Layout& l, double side);

// Bushes and hedges in the strip between the sidewalk and the buildings.
void add_front_gardens(Layout& l, double side);

void add_standing_people(Layout& l, double side);

// Sweeps a cross-section along the path over [s0, s1]: `outline` holds (offset to the left of
// `lateral`, height) points, joined in order (close it by repeating the first). Heights are above
// the road's centreline, or above the ground under `lateral` when `on_ground`.
void sweep_outline(Layout& l, double s0, double s1, double lateral,
                   const std::vector<Eigen::Vector2d>& outline, bool on_ground, uint32_t surface,
                   bool capped = false);

// A guard rail along [s0, s1] of the path `lateral` m left of the centreline; its posts stand on
// the side `outward` (+1: left) of the rail, behind it as seen from the road.
void add_guard_rail(Layout& l, double lateral, double outward, double s0, double s1);

}  // namespace adaptive_lego_loam::sim
