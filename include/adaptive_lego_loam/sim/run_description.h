#pragma once
// Everything a simulated sequence was made from, for its scenario.yaml: with the seed, the same
// settings give the same sequence byte for byte.

#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/sim/lidar_model.h"
#include "adaptive_lego_loam/sim/scenario.h"

namespace adaptive_lego_loam::sim {

struct RunDescription {
  std::string sensor;                                  // vlp16 | hdl64e
  std::string config_path;                             // the sensor config the geometry came from
  std::string trajectory_path, trajectory_times_path;  // empty: synthetic path
  SceneRequest request;  // its trajectory samples are not written, only their source
  SensorParams sensor_params;
  SimSensorOptions sensor_options;
  double path_length_m = 0.0, drive_length_m = 0.0;
  std::vector<SpeedChange> speed_changes;  // GeneratedScene's
  std::optional<double> tunnel_entry_m;
};

std::string run_yaml(const RunDescription& run);

}  // namespace adaptive_lego_loam::sim
