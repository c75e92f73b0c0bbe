#pragma once
// Part of the scene generator (scene_generator.cpp): what lines the road in each scenario.

#include <vector>

#include "placement.h"

namespace adaptive_lego_loam::sim {

void layout_urban(Layout& l, const std::vector<SideStreet>& side_streets);

// A highway is built in stretches of a few hundred metres, each with its median (double guard
// rail or concrete barrier) and, on each side, a guard rail in front of open verges and fields,
// a noise wall, an earth berm or the slope of a cutting.
enum class Roadside { kOpen, kNoiseWall, kBerm, kCutting };

struct HighwayStretch {
  double s0 = 0.0, s1 = 0.0;
  bool concrete_median = false;
  Roadside roadside[2] = {Roadside::kOpen, Roadside::kOpen};  // [0] right, [1] left
  double height[2] = {0.0, 0.0};                              // of the noise wall or berm
};

constexpr double kNoiseWallOffset = 2.5;  // behind the road's edge
constexpr double kBermToeOffset = 6.0;    // past the ditch

std::vector<HighwayStretch> plan_highway(const ScenarioParams& p, const Path& path, Rng& rng);

std::vector<Berm> highway_berms(const std::vector<HighwayStretch>& stretches, double half_width);

void layout_highway(Layout& l, const std::vector<HighwayStretch>& stretches);

void layout_vegetation(Layout& l);

}  // namespace adaptive_lego_loam::sim
