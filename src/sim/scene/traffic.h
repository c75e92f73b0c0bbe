#pragma once
// Part of the scene generator (scene_generator.cpp): moving cars and walking people.

#include "adaptive_lego_loam/sim/random.h"
#include "adaptive_lego_loam/sim/scenario.h"

namespace adaptive_lego_loam::sim {

// Cars in other lanes at their own speeds. In the ego vehicle's lane only on an open synthetic
// path, ahead and faster or behind and slower, so that nothing drives through the ego vehicle;
// only ahead when the ego vehicle `slows_down` on the way (it would be run into).
void add_moving_cars(World& world, const Path& path, const ScenarioParams& p, double ego_start_s,
                     bool ego_lane_allowed, bool slows_down, Rng& rng);

void add_walkers(World& world, const Path& path, const ScenarioParams& p, Rng& rng);

}  // namespace adaptive_lego_loam::sim
