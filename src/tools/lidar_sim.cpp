// Simulates LiDAR sequences with exact ground truth in the scenes the paper is about (urban,
// highway, tunnel, vegetation, loop) and degenerate ones (a bare tunnel, an indoor corridor), and
// writes them as KITTI-style folders, optionally a bag.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <boost/make_shared.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nav_msgs/Odometry.h>
#include <ros/message_traits.h>
#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/config_fit.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/progress.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"
#include "adaptive_lego_loam/ros/motion_sensor_conversions.h"
#include "adaptive_lego_loam/ros/pose_conversions.h"
#include "adaptive_lego_loam/sim/imu_model.h"
#include "adaptive_lego_loam/sim/motion_sensor_faults.h"
#include "adaptive_lego_loam/sim/run_description.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/sensor_presets.h"
#include "adaptive_lego_loam/sim/sequence_writer.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "adaptive_lego_loam/sim/wheel_odometry_model.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;
using namespace adaptive_lego_loam::sim;

namespace {

// Bag stamps start here (s): some ROS tools treat small stamps as "no time".
constexpr double kBagStartStamp = 1.0e9;

struct Options {
  std::string scenario, sensor, config_path, output, trajectory, trajectory_times, bag;
  int frames = 0;
  uint64_t seed = 1;
  std::optional<uint64_t> scene_seed;
  int laps = 1;
  std::optional<int> columns;
  std::optional<double> range_noise;
  std::optional<double> beam_divergence;
  std::optional<std::string> motion_distortion, rough_road;
  std::optional<double> speed, leaf_jitter, foliage_density, scan_period;
  std::optional<double> sensor_height;
  bool identical_houses = false;
  bool overwrite = false;
  // Motion sensors.
  bool imu = false, wheel_odometry = false;
  double imu_rate = 200.0, odom_rate = 50.0;
  std::vector<std::string> motion_errors{"all"};
  bool perfect_motion_sensors = false;
  std::vector<double> imu_mount;
  std::string sensor_faults;
};

const std::vector<std::string> kMotionErrors = {
    "all",         "none",        "imu-noise",  "imu-bias-walk", "imu-turn-on-bias",
    "wheel-scale", "wheel-noise", "wheel-slips"};

// The sensor's config: the preset's unless --config names another.
void resolve_sensor(Options& o) {
  if (o.config_path.empty())
    o.config_path = std::string(CONFIG_DIR) + "/" + sensor_preset(o.sensor).config_file;
}

bool on_off(const std::optional<std::string>& value, bool fallback) {
  return value ? *value == "on" : fallback;
}

SceneRequest make_request(const Options& o, const SensorParams& sensor) {
  SceneRequest request;
  request.scenario = named_scenario(o.scenario);
  if (o.speed) request.scenario.cruise_speed_mps = *o.speed;
  if (o.leaf_jitter) request.scenario.leaf_jitter_m = *o.leaf_jitter;
  if (o.foliage_density) request.scenario.foliage_density = *o.foliage_density;
  if (o.identical_houses) {
    // Every place alike: the same house on every lot, no side streets, no trees or bushes.
    request.scenario.identical_houses = true;
    request.scenario.junctions_per_km = 0.0;
    request.scenario.trees_per_100m = 0.0;
    request.scenario.bushes_per_100m = 0.0;
  }
  request.scenario.rough_road = on_off(o.rough_road, request.scenario.rough_road);
  request.seed = o.seed;
  request.scene_seed = o.scene_seed;
  request.laps = o.laps;
  request.frames = o.frames;
  request.frame_period = sensor.scan_period;
  request.sensor_height = o.sensor_height;
  request.reach = sensor.max_range;
  if (!o.trajectory.empty()) {
    request.trajectory_poses =
        camera_poses_to_vehicle_axes(adaptive_lego_loam::read_kitti_poses(o.trajectory));
    if (static_cast<std::size_t>(o.frames) > request.trajectory_poses.size()) {
      throw std::invalid_argument("--frames " + std::to_string(o.frames) + " exceeds the " +
                                  std::to_string(request.trajectory_poses.size()) + " poses of " +
                                  o.trajectory);
    }
    if (!o.trajectory_times.empty()) {
      request.trajectory_times = read_kitti_times(o.trajectory_times);
      const auto& times = request.trajectory_times;
      for (std::size_t i = 1; i < times.size(); ++i) {
        if (!(times[i] > times[i - 1])) {
          throw IoError(o.trajectory_times + ":" + std::to_string(i + 1) + ": times must increase");
        }
      }
      if (request.trajectory_times.size() != request.trajectory_poses.size()) {
        throw IoError(o.trajectory_times + ": " + std::to_string(request.trajectory_times.size()) +
                      " times for the " + std::to_string(request.trajectory_poses.size()) +
                      " poses of " + o.trajectory);
      }
    } else {
      for (std::size_t i = 0; i < request.trajectory_poses.size(); ++i)
        request.trajectory_times.push_back(i * sensor.scan_period);
    }
  }
  return request;
}

bool error_on(const Options& o, const std::string& error) {
  if (o.perfect_motion_sensors) return false;
  const auto& list = o.motion_errors;
  const auto has = [&](const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  return !has("none") && (has("all") || has(error));
}

// The IMU and wheel odometry along the drive, on the scans' clock from the first sweep's start
// to the last scan, with the faults asked for.
struct MotionSensorData {
  std::optional<ImuDescription> imu;
  std::vector<ImuSample> imu_samples;
  std::optional<WheelOdometryDescription> wheel;
  std::vector<WheelOdometrySample> wheel_samples;
  std::vector<std::string> faults;
};

MotionSensorData simulate_motion_sensors(const Options& o, const GeneratedScene& scene,
                                         double scan_period, double sensor_height) {
  MotionSensorData data;
  const double from = scene.motion->frame_time(0) - scan_period;
  const double to = scene.motion->frame_time(o.frames - 1);
  const std::vector<SensorFault> faults =
      o.sensor_faults.empty() ? std::vector<SensorFault>() : parse_faults(o.sensor_faults);
  for (const SensorFault& fault : faults)
    data.faults.push_back(fault_name(fault));
  if (o.imu) {
    ImuOptions options;
    options.rate_hz = o.imu_rate;
    if (!o.imu_mount.empty()) {
      std::copy(o.imu_mount.begin(), o.imu_mount.begin() + 3, options.mount_rpy_deg.begin());
      std::copy(o.imu_mount.begin() + 3, o.imu_mount.end(), options.mount_xyz_m.begin());
    }
    options.white_noise = error_on(o, "imu-noise");
    options.bias_random_walk = error_on(o, "imu-bias-walk");
    options.turn_on_bias = error_on(o, "imu-turn-on-bias");
    const ImuModel model(options, o.seed);
    data.imu_samples = model.simulate(*scene.motion, from, to);
    apply_faults(faults, data.imu_samples);
    data.imu = ImuDescription{model.options(), model.errors()};
  }
  if (o.wheel_odometry) {
    WheelOdometryOptions options;
    options.rate_hz = o.odom_rate;
    options.mount_xyz_m[2] = -sensor_height;
    options.scale_error = error_on(o, "wheel-scale");
    options.noise = error_on(o, "wheel-noise");
    options.slips = error_on(o, "wheel-slips");
    const WheelOdometryModel model(options, o.seed);
    WheelOdometryRun run = model.simulate(*scene.motion, from, to);
    data.wheel_samples = std::move(run.samples);
    apply_faults(faults, data.wheel_samples);
    data.wheel = WheelOdometryDescription{model.options(), model.errors(), run.slips};
  }
  return data;
}

// A message type's connection header for rosbag, latched as a static transform's publisher is.
template <typename Message>
boost::shared_ptr<ros::M_string> latched_connection() {
  auto header = boost::make_shared<ros::M_string>();
  (*header)["type"] = ros::message_traits::datatype<Message>();
  (*header)["md5sum"] = ros::message_traits::md5sum<Message>();
  (*header)["message_definition"] = ros::message_traits::definition<Message>();
  (*header)["callerid"] = "/lidar_sim";
  (*header)["latching"] = "1";
  return header;
}

class BagOutput {
 public:
  BagOutput(const std::string& path, const MotionSensorData& motion)
      : motion_(motion), odometry_poses_(integrate_odometry(motion.wheel_samples)) {
    bag_.open(path, rosbag::bagmode::Write);
    if (motion.imu && motion.imu->options.white_noise) {
      gyro_variance_ = std::pow(motion.imu->options.gyro_noise_sigma(), 2);
      accel_variance_ = std::pow(motion.imu->options.accel_noise_sigma(), 2);
    }
  }

  // velodyne -> imu and base_link -> velodyne on /tf_static, at the bag's start.
  void write_static_transforms(double time) {
    tf2_msgs::TFMessage transforms;
    std_msgs::Header header;
    header.stamp.fromSec(kBagStartStamp + time);
    if (motion_.imu) {
      header.frame_id = "velodyne";
      transforms.transforms.push_back(
          ros_bridge::transform_to_ros(motion_.imu->options.lidar_from_imu(), header, "imu"));
    }
    if (motion_.wheel) {
      header.frame_id = "base_link";
      transforms.transforms.push_back(ros_bridge::transform_to_ros(
          motion_.wheel->options.lidar_from_base().inverse(), header, "velodyne"));
    }
    if (transforms.transforms.empty()) return;
    bag_.write("/tf_static", header.stamp, transforms, latched_connection<tf2_msgs::TFMessage>());
  }

  // The motion sensors' samples up to `time` (s, the scans' clock): /imu/data and /odom.
  void write_motion_until(double time) {
    const auto& imu = motion_.imu_samples;
    for (; next_imu_ < imu.size() && imu[next_imu_].stamp <= time; ++next_imu_) {
      std_msgs::Header header;
      header.stamp.fromSec(kBagStartStamp + imu[next_imu_].stamp);
      header.frame_id = "imu";
      bag_.write("/imu/data", arrival(header.stamp),
                 ros_bridge::imu_to_ros(imu[next_imu_], header, gyro_variance_, accel_variance_));
    }
    const auto& wheel = motion_.wheel_samples;
    for (; next_wheel_ < wheel.size() && wheel[next_wheel_].stamp <= time; ++next_wheel_) {
      std_msgs::Header header;
      header.stamp.fromSec(kBagStartStamp + wheel[next_wheel_].stamp);
      header.frame_id = "odom";
      bag_.write("/odom", arrival(header.stamp),
                 ros_bridge::wheel_odometry_to_ros(wheel[next_wheel_], odometry_poses_[next_wheel_],
                                                   header, "base_link"));
    }
  }

  void write(const SimFrame& frame, const Eigen::Isometry3d& relative_pose) {
    std_msgs::Header header;
    header.stamp.fromSec(kBagStartStamp + frame.time);
    header.frame_id = "velodyne";
    bag_.write("/velodyne_points", header.stamp,
               ros_bridge::to_ros(frame.scan.points, header, true));
    nav_msgs::Odometry odometry;
    odometry.header.stamp = header.stamp;
    odometry.header.frame_id = "map";
    odometry.child_frame_id = "velodyne";
    const Eigen::Quaterniond rotation(relative_pose.linear());
    odometry.pose.pose.position.x = relative_pose.translation().x();
    odometry.pose.pose.position.y = relative_pose.translation().y();
    odometry.pose.pose.position.z = relative_pose.translation().z();
    odometry.pose.pose.orientation.w = rotation.w();
    odometry.pose.pose.orientation.x = rotation.x();
    odometry.pose.pose.orientation.y = rotation.y();
    odometry.pose.pose.orientation.z = rotation.z();
    bag_.write("/ground_truth", header.stamp, odometry);
  }

 private:
  // When a message is written: in stamp order, but a stamp out of order (a fault) arrives
  // after the ones before it.
  ros::Time arrival(const ros::Time& stamp) {
    latest_ = std::max(latest_, stamp);
    return latest_;
  }

  rosbag::Bag bag_;
  const MotionSensorData& motion_;
  std::vector<Eigen::Isometry3d> odometry_poses_;
  std::size_t next_imu_ = 0, next_wheel_ = 0;
  double gyro_variance_ = 0.0, accel_variance_ = 0.0;
  ros::Time latest_;
};

// The shipped configs (config/*.yaml) that read what was written: the folder's scans (no ring
// field) and the bag's clouds (ring field).
void print_matching_configs(const SensorParams& sensor, int firings, bool bag) {
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(CONFIG_DIR)) {
    if (entry.path().extension() == ".yaml") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  for (const bool ring_field : {false, true}) {
    if (ring_field && !bag) continue;
    std::string names;
    for (const std::string& path : paths) {
      try {
        if (config_reads(load_config(path).sensor, sensor, firings, ring_field)) {
          names += (names.empty() ? " config/" : ", config/") +
                   std::filesystem::path(path).filename().string();
        }
      } catch (const ConfigError&) {
      }
    }
    std::printf(
        "lidar_sim: %s fit%s\n",
        ring_field ? "the bag's clouds (with a ring field)"
                   : "the scans in velodyne/ (no ring field)",
        names.empty() ? " none of the shipped configs: derive_config measures one" : names.c_str());
  }
}

void print_class_shares(const std::map<uint16_t, long>& counts, long total) {
  std::printf("lidar_sim: points per class:");
  for (const auto& [semantic, count] : counts) {
    std::printf(" %s %.1f %%", class_name(static_cast<SemanticClass>(semantic)).c_str(),
                100.0 * count / std::max(total, 1L));
  }
  std::printf("\n");
}

int run(Options& o) {
  resolve_sensor(o);
  Config config = load_config(o.config_path);
  if (o.scan_period) config.sensor.scan_period = *o.scan_period;
  SimSensorOptions sensor_options = preset_options(sensor_preset(o.sensor), config.sensor);
  if (o.columns) sensor_options.columns = *o.columns;
  if (o.range_noise) sensor_options.range_noise_m = *o.range_noise;
  if (o.beam_divergence) sensor_options.beam_divergence_mrad = *o.beam_divergence;
  // KITTI ships de-skewed scans (its config says deskewed: true); a raw VLP-16 does not.
  sensor_options.motion_distortion = on_off(o.motion_distortion, !config.sensor.deskewed);
  const LidarModel model(config.sensor, sensor_options);

  const auto build_started = std::chrono::steady_clock::now();
  const SceneRequest request = make_request(o, config.sensor);
  SequenceWriter writer(o.output, o.overwrite, sensor_options.range_noise_m);
  const GeneratedScene scene = generate_scene(request);
  LidarSimulator simulator(model, scene.world, scene.trajectory, o.seed);
  const double build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - build_started).count();
  std::printf(
      "lidar_sim: %s with %s (%d beams x %d columns, %s), seed %llu: %zu plants, %zu "
      "moving cars, %zu walkers along %.0f m of road; scene built in %.2f s\n",
      o.scenario.c_str(), o.sensor.c_str(), model.beams(), model.columns(), o.config_path.c_str(),
      static_cast<unsigned long long>(o.seed), scene.world->plants.size(),
      scene.world->moving_cars.size(), scene.world->walkers.size(), scene.path_length_m,
      build_seconds);

  const MotionSensorData motion =
      simulate_motion_sensors(o, scene, config.sensor.scan_period, request.height());
  std::unique_ptr<BagOutput> bag;
  if (!o.bag.empty()) {
    bag = std::make_unique<BagOutput>(o.bag, motion);
    bag->write_static_transforms(scene.motion->frame_time(0) - config.sensor.scan_period);
  }
  ProgressBar progress("lidar_sim", o.frames);
  std::map<uint16_t, long> class_counts;
  long points = 0;
  const auto started = std::chrono::steady_clock::now();
  const std::clock_t cpu_started = std::clock();
  SimFrame simulated;
  for (int frame = 0; frame < o.frames; ++frame) {
    simulator.render(frame, simulated);
    writer.write_frame(frame, simulated);
    if (bag) {
      bag->write_motion_until(simulated.time);
      bag->write(simulated, writer.relative_poses().back());
    }
    for (uint32_t label : simulated.labels)
      ++class_counts[static_cast<uint16_t>(label & 0xFFFFu)];
    points += static_cast<long>(simulated.labels.size());
    progress.update(frame + 1);
  }
  progress.finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const double cpu_seconds = static_cast<double>(std::clock() - cpu_started) / CLOCKS_PER_SEC;

  RunDescription description;
  description.sensor = o.sensor;
  description.config_path = o.config_path;
  description.trajectory_path = o.trajectory;
  description.trajectory_times_path = o.trajectory_times;
  description.request = request;
  description.request.trajectory_poses.clear();
  description.request.trajectory_times.clear();
  description.sensor_params = config.sensor;
  description.sensor_options = sensor_options;
  description.path_length_m = scene.path_length_m;
  description.drive_length_m = scene.drive_length_m;
  description.trajectory_cutoff_hz = scene.motion->position_cutoff_hz();
  description.imu = motion.imu;
  description.wheel_odometry = motion.wheel;
  description.sensor_faults = motion.faults;
  if (motion.imu) writer.write_imu(motion.imu_samples);
  if (motion.wheel) writer.write_wheel_odometry(motion.wheel_samples);
  if (motion.imu || motion.wheel) writer.write_sensors_yaml(sensors_yaml(description));
  description.speed_changes = scene.speed_changes;
  description.tunnel_entry_m = scene.tunnel_entry_m;
  writer.finish(run_yaml(description));

  print_class_shares(class_counts, points);
  print_matching_configs(config.sensor, model.columns(), bag != nullptr);
  std::printf("lidar_sim: %.0f points per frame; ray casting %.2f s\n",
              static_cast<double>(points) / o.frames, simulator.ray_casting_seconds());
  // CPU time too: on a shared machine the wall clock also counts other processes' turns.
  std::printf(
      "lidar_sim: %d frames in %.2f s (%.1f frames/s, single thread; %.1f frames/s of CPU "
      "time)\n",
      o.frames, seconds, o.frames / seconds, o.frames / cpu_seconds);
  return tools::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Simulate a LiDAR sequence with exact ground truth (poses, per-point semantic and instance "
      "labels) in a generated scene, written as a KITTI-style folder."};
  Options o;
  app.add_option("--scenario", o.scenario,
                 "scene: urban, highway, tunnel (a road tunnel with its furniture, entered from "
                 "open road), vegetation, loop, green_highway (the highway with planted verges, as "
                 "KITTI 01), busy_street (crowded, as KITTI 04), bare_tunnel (smooth walls, "
                 "straight) or corridor (indoors, a robot's sensor)")
      ->required()
      ->check(CLI::IsMember(scenario_names()));
  app.add_option("--sensor", o.sensor,
                 "vlp16, hdl64e (KITTI's, config/kitti.yaml), os0_64, os1_64, os1_128, os2_128, "
                 "pandar_xt32, pandar_qt64 or rs_helios_32 (config/SENSOR.yaml)")
      ->required()
      ->check(CLI::IsMember(sensor_preset_names()));
  app.add_option("--config", o.config_path, "sensor config to take the beam geometry from instead");
  app.add_option("--frames", o.frames, "number of scans")
      ->required()
      ->check(CLI::Range(1, 1000000));
  app.add_option("--seed", o.seed,
                 "seed of the noise, wind and moving objects, and of the scene and trajectory "
                 "unless --scene-seed is given (default 1)");
  app.add_option("--scene-seed", o.scene_seed,
                 "seed of the scene, its path and the drive along it: the same place driven "
                 "again with another --seed");
  app.add_option("--laps", o.laps, "a loop scenario goes round this many times (default 1)")
      ->check(CLI::Range(1, 100));
  app.add_option("--output", o.output, "folder to write the sequence to")->required();
  app.add_option(
      "--trajectory", o.trajectory,
      "KITTI ground-truth pose file (camera frame) to drive instead of a synthetic path");
  app.add_option("--trajectory-times", o.trajectory_times,
                 "KITTI times file for --trajectory (default: one pose per scan period)");
  app.add_option("--bag", o.bag,
                 "also write a rosbag: /velodyne_points (x y z intensity ring time) "
                 "and /ground_truth (nav_msgs/Odometry)");
  app.add_option("--scan-period", o.scan_period,
                 "seconds a turn (default: the config's scan_period; 0.05 at 20 Hz, 0.2 at 5 Hz); "
                 "with --columns for a sensor whose firings per turn change with the rate")
      ->check(CLI::Range(0.01, 1.0));
  app.add_option("--columns", o.columns,
                 "firings per turn (default: the config's columns; 2083 for hdl64e)")
      ->check(CLI::Range(16, 20000));
  app.add_option("--range-noise", o.range_noise,
                 "standard deviation of the range error, m (default: the sensor's, 0.01-0.03)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--beam-divergence", o.beam_divergence,
                 "beam divergence, mrad: echoes within a footprint mix at edges and in foliage "
                 "(default: the sensor's, 1.6-6.1; 3 vlp16, 2 hdl64e; 0: thin beams)")
      ->check(CLI::Range(0.0, 50.0));
  app.add_option("--motion-distortion", o.motion_distortion,
                 "on|off (default: off when the config says deskewed, as KITTI's, else on)")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--rough-road", o.rough_road,
                 "on|off: shake the sensor (default: on for vegetation)")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--speed", o.speed, "cruise speed on a synthetic path, m/s (default per scenario)")
      ->check(CLI::Range(0.1, 70.0));
  app.add_option("--leaf-jitter", o.leaf_jitter,
                 "leaf movement between scans (wind), m (default 0.04)")
      ->check(CLI::Range(0.0, 0.5));
  app.add_option(
         "--foliage-density", o.foliage_density,
         "how far beams get into trees and bushes: a multiple of the default extinction "
         "(11.2/m trees, 22.4/m bushes, as dense as KITTI's foliage), with as many more leaves "
         "of the same size (default 1)")
      ->check(CLI::Range(0.05, 2.0));
  app.add_option("--sensor-height", o.sensor_height,
                 "sensor height above the road or floor, m (default 1.73; corridor 0.6)")
      ->check(CLI::Range(0.2, 5.0));
  app.add_flag("--identical-houses", o.identical_houses,
               "urban or loop: the same house on every lot, no side streets, trees or bushes (a "
               "street where every place looks alike)");
  app.add_flag("--overwrite", o.overwrite, "replace a sequence already in --output");
  app.add_flag("--imu", o.imu,
               "also simulate an IMU (ADIS16448, mounted rotated and offset from the LiDAR): "
               "imu.csv, sensors.yaml and, with --bag, /imu/data and /tf_static");
  app.add_flag("--wheel-odom", o.wheel_odometry,
               "also simulate a wheel odometry (the rear axle's forward speed and yaw rate): "
               "wheel_odom.csv, sensors.yaml and, with --bag, /odom and /tf_static");
  app.add_option("--imu-rate", o.imu_rate, "IMU samples per second (default 200)")
      ->check(CLI::Range(1.0, 2000.0));
  app.add_option("--odom-rate", o.odom_rate, "wheel odometry samples per second (default 50)")
      ->check(CLI::Range(1.0, 1000.0));
  app.add_option("--motion-errors", o.motion_errors,
                 "the motion sensors' errors to simulate: all (default), none, or a list of "
                 "imu-noise, imu-bias-walk, imu-turn-on-bias, wheel-scale, wheel-noise, "
                 "wheel-slips")
      ->delimiter(',')
      ->check(CLI::IsMember(kMotionErrors));
  app.add_flag("--perfect-motion-sensors", o.perfect_motion_sensors,
               "the motion sensors without any error (as --motion-errors none)");
  app.add_option("--imu-mount", o.imu_mount,
                 "the IMU's pose in the LiDAR frame: roll,pitch,yaw (deg, R = Rz Ry Rx),x,y,z "
                 "(m) (default 180,2.5,90,-0.12,0.08,-0.18)")
      ->delimiter(',')
      ->expected(6);
  app.add_option("--sensor-faults", o.sensor_faults,
                 "faults in the motion sensors' samples: SENSOR:KIND@TIME,... with SENSOR imu or "
                 "wheel, KIND nan, repeat, disorder, gap (2 s), rate_drop (2 s at a quarter "
                 "rate) or absurd, TIME in s (docs/simulator.md)");
  if (const auto status = tools::parse_command_line(app, argc, argv, "lidar_sim")) return *status;
  if (!o.trajectory_times.empty() && o.trajectory.empty()) {
    return tools::usage_error("lidar_sim", "--trajectory-times needs --trajectory");
  }
  bool motion_options = false;
  for (const char* option : {"--imu-rate", "--odom-rate", "--motion-errors",
                             "--perfect-motion-sensors", "--imu-mount", "--sensor-faults"})
    motion_options |= app.count(option) > 0;
  if (motion_options && !o.imu && !o.wheel_odometry) {
    return tools::usage_error("lidar_sim",
                              "the motion sensors' options need --imu or --wheel-odom");
  }
  if (!o.sensor_faults.empty()) {
    try {
      parse_faults(o.sensor_faults);
    } catch (const std::invalid_argument& error) {
      return tools::usage_error("lidar_sim", std::string("--sensor-faults ") + error.what());
    }
  }
  if (!o.trajectory.empty() && o.speed) {
    return tools::usage_error("lidar_sim",
                              "--speed applies to synthetic paths only, not with --trajectory");
  }
  return tools::run_job("lidar_sim", [&] { return run(o); });
}
