#include "adaptive_lego_loam/sim/sensor_presets.h"

#include <stdexcept>

namespace adaptive_lego_loam::sim {

const std::vector<SensorPreset>& sensor_presets() {
  // Divergence: the datasheets' full angle; noise: their range precision (1 sigma). The HDL-64E
  // is KITTI's (kitti.yaml's measured beams and origins); its config has 2200 columns of
  // range-image headroom, the sensor fires about 2083 times a turn at 10 Hz.
  static const std::vector<SensorPreset> presets = {
      {"vlp16", "vlp16.yaml", 0, 3.0, 0.02},
      {"hdl64e", "kitti.yaml", 2083, 2.0, 0.02},
      {"os0_64", "os0_64.yaml", 0, 6.1, 0.03},
      {"os1_64", "os1_64.yaml", 0, 3.1, 0.03},
      {"os1_128", "os1_128.yaml", 0, 3.1, 0.03},
      {"os2_128", "os2_128.yaml", 0, 1.6, 0.03},
      {"pandar_xt32", "pandar_xt32.yaml", 0, 2.0, 0.01},
      {"pandar_qt64", "pandar_qt64.yaml", 0, 2.0, 0.02},
      {"rs_helios_32", "rs_helios_32.yaml", 0, 2.0, 0.02},
  };
  return presets;
}

std::vector<std::string> sensor_preset_names() {
  std::vector<std::string> names;
  for (const SensorPreset& preset : sensor_presets())
    names.push_back(preset.name);
  return names;
}

const SensorPreset& sensor_preset(const std::string& name) {
  std::string known;
  for (const SensorPreset& preset : sensor_presets()) {
    if (preset.name == name) return preset;
    known += (known.empty() ? "" : ", ") + preset.name;
  }
  throw std::invalid_argument("unknown sensor '" + name + "'; expected one of: " + known);
}

SimSensorOptions preset_options(const SensorPreset& preset, const SensorParams& sensor) {
  SimSensorOptions options;
  options.columns = preset.firings > 0 ? preset.firings : sensor.columns;
  options.beam_divergence_mrad = preset.beam_divergence_mrad;
  options.range_noise_m = preset.range_noise_m;
  return options;
}

}  // namespace adaptive_lego_loam::sim
