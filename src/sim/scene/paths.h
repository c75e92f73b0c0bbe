#pragma once
// Part of the scene generator (scene_generator.cpp): the path of a synthetic drive or under a
// recorded trajectory.

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "adaptive_lego_loam/sim/random.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/terrain.h"

namespace adaptive_lego_loam::sim {

std::vector<PathPiece> open_pieces(ScenarioKind kind, double length, double lead, Rng& rng);

// A rounded rectangle (3:2) of the given length, counter-clockwise.
std::vector<PathPiece> loop_pieces(double length);

std::shared_ptr<const Path> synthetic_path(const std::vector<PathPiece>& pieces, bool closed,
                                           const HeightField& hills);

// The road under a recorded trajectory: the centreline lies `-ego_lateral` to the left of the
// vehicle, and runs on straight for `lead` metres before the first pose and after the last.
std::shared_ptr<const Path> recorded_path(const std::vector<Eigen::Isometry3d>& sensor_poses,
                                          double sensor_height, double ego_lateral, double lead);

}  // namespace adaptive_lego_loam::sim
