#pragma once
// Scene requests and simulated frames for the scenario tests.

#include <vector>

#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "sim/sim_sensors.h"

namespace adaptive_lego_loam::sim::test {

constexpr int kFrames = 3;

inline SceneRequest request_for(ScenarioKind kind, uint64_t seed, int frames = kFrames) {
  SceneRequest request;
  request.scenario = default_scenario(kind);
  request.seed = seed;
  request.frames = frames;
  request.reach = vlp16().max_range;
  return request;
}

inline std::vector<SimFrame> simulate(ScenarioKind kind, uint64_t seed, int frames = kFrames) {
  const GeneratedScene scene = generate_scene(request_for(kind, seed, frames));
  SimSensorOptions options;
  options.columns = 1800;
  LidarSimulator simulator(LidarModel(vlp16(), options), scene.world, scene.trajectory, seed);
  std::vector<SimFrame> out;
  for (int frame = 0; frame < frames; ++frame)
    out.push_back(simulator.render(frame));
  return out;
}

// The frames of each scenario with seed 3, simulated once for all tests.
inline const std::vector<SimFrame>& frames_of(ScenarioKind kind) {
  static std::map<ScenarioKind, std::vector<SimFrame>> cache;
  auto found = cache.find(kind);
  if (found == cache.end()) found = cache.emplace(kind, simulate(kind, 3)).first;
  return found->second;
}

}  // namespace adaptive_lego_loam::sim::test
