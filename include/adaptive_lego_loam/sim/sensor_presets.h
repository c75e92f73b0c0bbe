#pragma once
// The sensors lidar_sim models by name: each a shipped config (its beams, range limits, ring
// numbering and scan period) and what the config does not hold, its firings per turn, beam
// divergence and range noise, from the maker's datasheet.

#include <string>
#include <vector>

#include "adaptive_lego_loam/sim/lidar_model.h"

namespace adaptive_lego_loam::sim {

struct SensorPreset {
  std::string name;         // lidar_sim --sensor
  std::string config_file;  // in config/
  int firings = 0;          // per turn; 0: the config's columns
  double beam_divergence_mrad = 2.0;
  double range_noise_m = 0.02;
};

const std::vector<SensorPreset>& sensor_presets();
std::vector<std::string> sensor_preset_names();
// Throws std::invalid_argument naming the known presets.
const SensorPreset& sensor_preset(const std::string& name);

// The preset's firings (or the sensor's columns), beam divergence and range noise.
SimSensorOptions preset_options(const SensorPreset& preset, const SensorParams& sensor);

}  // namespace adaptive_lego_loam::sim
