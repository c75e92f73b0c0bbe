#include "adaptive_lego_loam/sim/run_description.h"

#include <yaml-cpp/yaml.h>

#include <cmath>

namespace adaptive_lego_loam::sim {
namespace {

void emit_scenario(YAML::Emitter& out, const ScenarioParams& p) {
  out << YAML::Key << "scenario" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << p.name;
  out << YAML::Key << "kind" << YAML::Value << kind_name(p.kind);
  out << YAML::Key << "road_half_width_m" << YAML::Value << p.road_half_width;
  out << YAML::Key << "sidewalk_width_m" << YAML::Value << p.sidewalk_width;
  out << YAML::Key << "curb_height_m" << YAML::Value << p.curb_height;
  out << YAML::Key << "ego_lateral_m" << YAML::Value << p.ego_lateral;
  out << YAML::Key << "cruise_speed_mps" << YAML::Value << p.cruise_speed_mps;
  out << YAML::Key << "speed_variation" << YAML::Value << p.speed_variation;
  out << YAML::Key << "hill_amplitude_m" << YAML::Value << p.hill_amplitude_m;
  out << YAML::Key << "hill_wavelength_m" << YAML::Value << p.hill_wavelength_m;
  out << YAML::Key << "relief_amplitude_m" << YAML::Value << p.relief_amplitude_m;
  out << YAML::Key << "relief_wavelength_m" << YAML::Value << p.relief_wavelength_m;
  out << YAML::Key << "buildings" << YAML::Value << p.buildings;
  out << YAML::Key << "trees_per_100m" << YAML::Value << p.trees_per_100m;
  out << YAML::Key << "bushes_per_100m" << YAML::Value << p.bushes_per_100m;
  out << YAML::Key << "poles_per_100m" << YAML::Value << p.poles_per_100m;
  out << YAML::Key << "parked_car_share" << YAML::Value << p.parked_car_share;
  out << YAML::Key << "moving_cars_per_km_lane" << YAML::Value << p.moving_cars_per_km_lane;
  out << YAML::Key << "walkers_per_100m" << YAML::Value << p.walkers_per_100m;
  out << YAML::Key << "standing_people_per_100m" << YAML::Value << p.standing_people_per_100m;
  out << YAML::Key << "walls_per_100m" << YAML::Value << p.walls_per_100m;
  out << YAML::Key << "fences_share" << YAML::Value << p.fences_share;
  out << YAML::Key << "house_share" << YAML::Value << p.house_share;
  out << YAML::Key << "identical_houses" << YAML::Value << p.identical_houses;
  out << YAML::Key << "planted_verges" << YAML::Value << p.planted_verges;
  out << YAML::Key << "concrete_median_share" << YAML::Value << p.concrete_median_share;
  out << YAML::Key << "noise_wall_share" << YAML::Value << p.noise_wall_share;
  out << YAML::Key << "berm_share" << YAML::Value << p.berm_share;
  out << YAML::Key << "cutting_share" << YAML::Value << p.cutting_share;
  out << YAML::Key << "junctions_per_km" << YAML::Value << p.junctions_per_km;
  out << YAML::Key << "guard_rails" << YAML::Value << p.guard_rails;
  out << YAML::Key << "tunnel" << YAML::Value << p.tunnel;
  // Keys of the scenarios that came later, only where they mean something: the other scenarios'
  // files stay as they were.
  if (p.kind == ScenarioKind::kTunnel) {
    out << YAML::Key << "tunnel_furniture" << YAML::Value << p.tunnel_furniture;
    out << YAML::Key << "tunnel_curve" << YAML::Value << p.tunnel_curve;
  }
  if (p.slow_speed_mps > 0.0)
    out << YAML::Key << "slow_speed_mps" << YAML::Value << p.slow_speed_mps;
  out << YAML::Key << "leaf_jitter_m" << YAML::Value << p.leaf_jitter_m;
  out << YAML::Key << "foliage_density" << YAML::Value << p.foliage_density;
  out << YAML::Key << "wind_states" << YAML::Value << p.wind_states;
  out << YAML::Key << "rough_road" << YAML::Value << p.rough_road;
  out << YAML::Key << "shake" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "vertical_m" << YAML::Value << p.shake.vertical_m;
  out << YAML::Key << "roll_deg" << YAML::Value << p.shake.roll_deg;
  out << YAML::Key << "pitch_deg" << YAML::Value << p.shake.pitch_deg;
  if (p.rough_road) {  // keys that came later: the smooth rides' files stay as they were
    const ShakeParams& s = p.shake;
    out << YAML::Key << "body_hz" << YAML::Value << YAML::Flow << YAML::BeginSeq << s.body_min_hz
        << s.body_max_hz << YAML::EndSeq;
    out << YAML::Key << "vibration_vertical_m" << YAML::Value << s.vibration_vertical_m;
    out << YAML::Key << "vibration_roll_pitch_deg" << YAML::Value << s.vibration_roll_pitch_deg;
    out << YAML::Key << "vibration_hz" << YAML::Value << YAML::Flow << YAML::BeginSeq
        << s.vibration_min_hz << s.vibration_max_hz << YAML::EndSeq;
  }
  out << YAML::EndMap;
  out << YAML::EndMap;
}

void emit_sensor(YAML::Emitter& out, const RunDescription& run) {
  const SensorParams& s = run.sensor_params;
  const SimSensorOptions& o = run.sensor_options;
  out << YAML::Key << "sensor" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << run.sensor;
  out << YAML::Key << "config" << YAML::Value << run.config_path;
  out << YAML::Key << "config_name" << YAML::Value << s.name;
  out << YAML::Key << "beams" << YAML::Value << s.rows;
  out << YAML::Key << "columns" << YAML::Value << o.columns;
  out << YAML::Key << "beam_angles_deg" << YAML::Value << YAML::Flow << s.beam_angles_deg;
  out << YAML::Key << "beam_offsets_m" << YAML::Value << YAML::Flow << s.beam_offsets_m;
  out << YAML::Key << "min_range_m" << YAML::Value << s.min_range;
  out << YAML::Key << "max_range_m" << YAML::Value << s.max_range;
  out << YAML::Key << "scan_period_s" << YAML::Value << s.scan_period;
  out << YAML::Key << "height_m" << YAML::Value << run.request.height();
  out << YAML::Key << "range_noise_m" << YAML::Value << o.range_noise_m;
  out << YAML::Key << "full_return_incidence_deg" << YAML::Value << o.full_return_incidence_deg;
  out << YAML::Key << "no_return_incidence_deg" << YAML::Value << o.no_return_incidence_deg;
  out << YAML::Key << "motion_distortion" << YAML::Value << o.motion_distortion;
  out << YAML::Key << "beam_divergence_mrad" << YAML::Value << o.beam_divergence_mrad;
  out << YAML::Key << "echo_merge_distance_m" << YAML::Value << o.echo_merge_distance_m;
  out << YAML::EndMap;
}

void emit_triple(YAML::Emitter& out, const char* key, const std::array<double, 3>& values) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << values[0] << values[1]
      << values[2] << YAML::EndSeq;
}

void emit_vector(YAML::Emitter& out, const char* key, const Eigen::Vector3d& v) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z()
      << YAML::EndSeq;
}

void emit_imu(YAML::Emitter& out, const ImuDescription& imu) {
  const ImuOptions& o = imu.options;
  const ImuDatasheet& d = o.datasheet;
  out << YAML::Key << "imu" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "datasheet" << YAML::Value << d.name;
  out << YAML::Key << "rate_hz" << YAML::Value << o.rate_hz;
  out << YAML::Key << "frame" << YAML::Value << "imu";
  emit_triple(out, "mount_rpy_deg", o.mount_rpy_deg);
  emit_triple(out, "mount_xyz_m", o.mount_xyz_m);
  out << YAML::Key << "gravity" << YAML::Value << o.gravity;
  out << YAML::Key << "gyro_noise_density" << YAML::Value << d.gyro_noise_density;
  out << YAML::Key << "accel_noise_density" << YAML::Value << d.accel_noise_density;
  out << YAML::Key << "gyro_bias_stability" << YAML::Value << d.gyro_bias_stability;
  out << YAML::Key << "accel_bias_stability" << YAML::Value << d.accel_bias_stability;
  out << YAML::Key << "gyro_bias_random_walk" << YAML::Value << d.gyro_bias_random_walk();
  out << YAML::Key << "accel_bias_random_walk" << YAML::Value << d.accel_bias_random_walk();
  out << YAML::Key << "gyro_turn_on_bias_sigma" << YAML::Value << d.gyro_turn_on_bias;
  out << YAML::Key << "accel_turn_on_bias_sigma" << YAML::Value << d.accel_turn_on_bias;
  out << YAML::Key << "white_noise" << YAML::Value << o.white_noise;
  out << YAML::Key << "bias_random_walk" << YAML::Value << o.bias_random_walk;
  out << YAML::Key << "turn_on_bias" << YAML::Value << o.turn_on_bias;
  emit_vector(out, "gyro_turn_on_bias", imu.errors.gyro_turn_on_bias);
  emit_vector(out, "accel_turn_on_bias", imu.errors.accel_turn_on_bias);
  out << YAML::EndMap;
}

void emit_wheel_odometry(YAML::Emitter& out, const WheelOdometryDescription& wheel) {
  const WheelOdometryOptions& o = wheel.options;
  out << YAML::Key << "wheel_odometry" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "rate_hz" << YAML::Value << o.rate_hz;
  out << YAML::Key << "frame" << YAML::Value << "base_link";
  emit_triple(out, "mount_rpy_deg", o.mount_rpy_deg);
  emit_triple(out, "mount_xyz_m", o.mount_xyz_m);
  out << YAML::Key << "track_width_m" << YAML::Value << o.track_width_m;
  out << YAML::Key << "wheel_speed_noise" << YAML::Value << (o.noise ? o.wheel_speed_noise : 0.0);
  out << YAML::Key << "scale_error" << YAML::Value << wheel.errors.scale_error;
  out << YAML::Key << "track_width_error" << YAML::Value << wheel.errors.track_width_error;
  out << YAML::Key << "slips_per_km" << YAML::Value << wheel.errors.slips_per_km;
  out << YAML::Key << "slips" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const SlipEvent& slip : wheel.slips) {
    out << YAML::BeginMap;
    out << YAML::Key << "start_s" << YAML::Value << slip.start_s;
    out << YAML::Key << "duration_s" << YAML::Value << slip.duration_s;
    out << YAML::Key << "excess" << YAML::Value << slip.excess;
    out << YAML::Key << "wheel" << YAML::Value << (slip.left_wheel ? "left" : "right");
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "reported_speed_sigma" << YAML::Value << o.reported_speed_sigma;
  out << YAML::Key << "reported_yaw_rate_sigma" << YAML::Value << o.reported_yaw_rate_sigma;
  out << YAML::EndMap;
}

}  // namespace

std::string run_yaml(const RunDescription& run) {
  YAML::Emitter out;
  out.SetDoublePrecision(10);
  out << YAML::BeginMap;
  out << YAML::Key << "generator" << YAML::Value << "adaptive_lego_loam lidar_sim";
  out << YAML::Key << "seed" << YAML::Value << run.request.seed;
  out << YAML::Key << "scene_seed" << YAML::Value << run.request.scene();
  if (run.request.laps != 1) out << YAML::Key << "laps" << YAML::Value << run.request.laps;
  out << YAML::Key << "frames" << YAML::Value << run.request.frames;
  out << YAML::Key << "frame_period_s" << YAML::Value << run.request.frame_period;
  out << YAML::Key << "trajectory" << YAML::Value
      << (run.trajectory_path.empty() ? std::string("synthetic") : run.trajectory_path);
  if (!run.trajectory_times_path.empty())
    out << YAML::Key << "trajectory_times" << YAML::Value << run.trajectory_times_path;
  out << YAML::Key << "path_length_m" << YAML::Value << run.path_length_m;
  out << YAML::Key << "drive_length_m" << YAML::Value << run.drive_length_m;
  if (run.trajectory_cutoff_hz > 0.0)
    out << YAML::Key << "trajectory_cutoff_hz" << YAML::Value << run.trajectory_cutoff_hz;
  if (run.tunnel_entry_m)
    out << YAML::Key << "tunnel_entry_m" << YAML::Value << *run.tunnel_entry_m;
  if (!run.speed_changes.empty()) {
    out << YAML::Key << "speed_changes" << YAML::Value << YAML::BeginSeq;
    for (const SpeedChange& change : run.speed_changes) {
      out << YAML::Flow << YAML::BeginMap;
      out << YAML::Key << "start_time_s" << YAML::Value << change.start_time_s;
      out << YAML::Key << "delta_mps" << YAML::Value << change.delta_mps;
      out << YAML::Key << "acceleration_mps2" << YAML::Value << change.acceleration_mps2;
      out << YAML::Key << "ramp_s" << YAML::Value << change.ramp_s;
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  emit_sensor(out, run);
  emit_scenario(out, run.request.scenario);
  if (run.imu) emit_imu(out, *run.imu);
  if (run.wheel_odometry) emit_wheel_odometry(out, *run.wheel_odometry);
  if (!run.sensor_faults.empty())
    out << YAML::Key << "sensor_faults" << YAML::Value << YAML::Flow << run.sensor_faults;
  out << YAML::Key << "labels" << YAML::Value
      << "uint32 per point: semantic class (SemanticKITTI ids) in the lower 16 bits, instance "
         "id in the upper 16";
  out << YAML::Key << "poses" << YAML::Value
      << "sensor pose at each scan's time (a skewed sweep's end), relative to the first frame's "
         "(KITTI 3x4)";
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string sensors_yaml(const RunDescription& run) {
  YAML::Emitter out;
  out.SetDoublePrecision(10);
  out << YAML::BeginMap;
  if (run.imu) {
    const ImuOptions& o = run.imu->options;
    const ImuDatasheet& d = o.datasheet;
    out << YAML::Key << "imu" << YAML::Value << YAML::BeginMap;
    emit_triple(out, "extrinsic_rpy_deg", o.mount_rpy_deg);
    emit_triple(out, "extrinsic_xyz_m", o.mount_xyz_m);
    out << YAML::Key << "time_offset_s" << YAML::Value << 0.0;
    out << YAML::Key << "gyro_noise_density" << YAML::Value << d.gyro_noise_density;
    out << YAML::Key << "accel_noise_density" << YAML::Value << d.accel_noise_density;
    out << YAML::Key << "gyro_bias_random_walk" << YAML::Value << d.gyro_bias_random_walk();
    out << YAML::Key << "accel_bias_random_walk" << YAML::Value << d.accel_bias_random_walk();
    out << YAML::Key << "gyro_bias_sigma" << YAML::Value << d.gyro_turn_on_bias;
    out << YAML::Key << "accel_bias_sigma" << YAML::Value << d.accel_turn_on_bias;
    out << YAML::Key << "gravity" << YAML::Value << o.gravity;
    out << YAML::EndMap;
  }
  if (run.wheel_odometry) {
    const WheelOdometryOptions& o = run.wheel_odometry->options;
    out << YAML::Key << "wheel_odometry" << YAML::Value << YAML::BeginMap;
    emit_triple(out, "extrinsic_rpy_deg", o.mount_rpy_deg);
    emit_triple(out, "extrinsic_xyz_m", o.mount_xyz_m);
    out << YAML::Key << "time_offset_s" << YAML::Value << 0.0;
    out << YAML::Key << "speed_sigma" << YAML::Value << o.reported_speed_sigma;
    out << YAML::Key << "yaw_rate_sigma_deg" << YAML::Value
        << o.reported_yaw_rate_sigma * 180.0 / M_PI;
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  return "# The simulated motion sensors' true extrinsics and noise (lidar_sim, from the IMU's\n"
         "# datasheet and the wheel odometry's model): sections to paste into a config.\n" +
         std::string(out.c_str()) + "\n";
}

}  // namespace adaptive_lego_loam::sim
