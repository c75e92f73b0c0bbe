#pragma once
// Part of the scene generator (scene_generator.cpp): an office building's corridors driven by a
// robot. Their walls, floor and ceiling are placed around the drive, not swept along a road.

#include "adaptive_lego_loam/sim/scenario.h"

namespace adaptive_lego_loam::sim {

// A corridor 2 x road_half_width wide with doors every 10 m on both sides, closed 3-8 m behind
// the start, and a 90 deg turn (left or right) into a second corridor. The robot drives its
// centreline at the cruise speed, stops twice for 2-4 s and slows to 0.5 m/s for the turn.
// Throws std::invalid_argument for a recorded trajectory (the corridor has no road to lay
// under one).
GeneratedScene generate_corridor(const SceneRequest& request, const Shake& shake);

}  // namespace adaptive_lego_loam::sim
