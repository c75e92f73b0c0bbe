#pragma once
// Everything a simulated sequence was made from, for its scenario.yaml: with the seed, the same
// settings give the same sequence byte for byte.

#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/sim/imu_model.h"
#include "adaptive_lego_loam/sim/lidar_model.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/wheel_odometry_model.h"

namespace adaptive_lego_loam::sim {

// A simulated IMU: its model and the errors drawn for the run.
struct ImuDescription {
  ImuOptions options;
  ImuErrors errors;
};

// A simulated wheel odometry: its model, the errors drawn and the slips of the drive.
struct WheelOdometryDescription {
  WheelOdometryOptions options;
  WheelOdometryErrors errors;
  std::vector<SlipEvent> slips;
};

struct RunDescription {
  std::string sensor;                                  // vlp16 | hdl64e
  std::string config_path;                             // the sensor config the geometry came from
  std::string trajectory_path, trajectory_times_path;  // empty: synthetic path
  SceneRequest request;  // its trajectory samples are not written, only their source
  SensorParams sensor_params;
  SimSensorOptions sensor_options;
  double path_length_m = 0.0, drive_length_m = 0.0;
  double trajectory_cutoff_hz = 0.0;  // the smooth trajectory's position cutoff (0: through)
  std::optional<ImuDescription> imu;
  std::optional<WheelOdometryDescription> wheel_odometry;
  std::vector<std::string> sensor_faults;  // as parse_faults reads them
  std::vector<SpeedChange> speed_changes;  // GeneratedScene's
  std::optional<double> tunnel_entry_m;
};

std::string run_yaml(const RunDescription& run);

// The run's motion sensors as a config's imu: and wheel_odometry: sections (the keys
// load_config reads), with their true extrinsics and noise: for sensors.yaml.
std::string sensors_yaml(const RunDescription& run);

}  // namespace adaptive_lego_loam::sim
