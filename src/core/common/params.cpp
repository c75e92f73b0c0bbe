#include "adaptive_lego_loam/core/common/params.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace adaptive_lego_loam {

const char* to_string(EuclideanCriterion criterion) {
  return criterion == EuclideanCriterion::kDistance ? "distance" : "range_difference";
}

const char* to_string(Beta0Mode mode) {
  switch (mode) {
    case Beta0Mode::kAdaptive:
      return "adaptive";
    case Beta0Mode::kFixed:
      return "fixed";
    case Beta0Mode::kNone:
      return "none";
  }
  return "unknown";
}
namespace {

// A mapping key as text. YAML also allows a list or a mapping as a key, which names nothing here
// (and which yaml-cpp refuses to convert to text with an exception of its own).
std::string key_name(const YAML::Node& key, const std::string& source, const std::string& mapping) {
  if (key.IsScalar()) return key.Scalar();
  throw ConfigError(source + ": " + mapping + ": the key at line " +
                    std::to_string(key.Mark().line + 1) +
                    " is not a name (a list, a mapping or null)");
}

// Reads the keys of one YAML mapping, checking type and range, and remembers which keys it read
// so that anything else in the mapping can be reported as unknown.
class SectionReader {
 public:
  SectionReader(const YAML::Node& node, std::string path, std::string source)
      : node_(node), path_(std::move(path)), source_(std::move(source)) {
    if (node_ && !node_.IsMap()) fail(path_, "expected a mapping of keys");
  }

  template <typename T>
  void number(const char* key, T& value, T lo, T hi) {
    const YAML::Node item = find(key);
    if (!item) return;
    T parsed{};
    if (!item.IsScalar() || !YAML::convert<T>::decode(item, parsed)) {
      fail(full(key), "expected " + kind<T>() + " in " + range(lo, hi));
    }
    if (!(parsed >= lo && parsed <= hi)) {
      throw ConfigError(source_ + ": " + full(key) + " = " + item.Scalar() +
                        " is out of range: expected " + kind<T>() + " in " + range(lo, hi));
    }
    value = parsed;
  }

  void boolean(const char* key, bool& value) {
    const YAML::Node item = find(key);
    if (!item) return;
    if (!item.IsScalar() || !YAML::convert<bool>::decode(item, value)) {
      fail(full(key), "expected true or false");
    }
  }

  void text(const char* key, std::string& value) {
    const YAML::Node item = find(key);
    if (!item) return;
    if (!item.IsScalar()) fail(full(key), "expected a string");
    value = item.Scalar();
  }

  template <typename Enum>
  void choice(const char* key, Enum& value,
              const std::vector<std::pair<std::string, Enum>>& options) {
    const YAML::Node item = find(key);
    if (!item) return;
    std::string allowed;
    for (const auto& [name, option] : options) {
      if (item.IsScalar() && item.Scalar() == name) {
        value = option;
        return;
      }
      allowed += (allowed.empty() ? "" : ", ") + name;
    }
    fail(full(key), "expected one of: " + allowed);
  }

  template <typename T>
  void list(const char* key, std::vector<T>& values, T lo, T hi) {
    const YAML::Node item = find(key);
    if (!item) return;
    if (!item.IsSequence()) fail(full(key), "expected a list of " + kind<T>() + "s");
    values.clear();
    for (std::size_t i = 0; i < item.size(); ++i) {
      T parsed{};
      if (!item[i].IsScalar() || !YAML::convert<T>::decode(item[i], parsed) ||
          !(parsed >= lo && parsed <= hi)) {
        fail(full(key) + "[" + std::to_string(i) + "]",
             "expected " + kind<T>() + " in " + range(lo, hi));
      }
      values.push_back(parsed);
    }
  }

  bool has(const char* key) const { return node_ && node_[key]; }

  void reject_unknown_keys() const {
    if (!node_) return;
    for (const auto& entry : node_) {
      const std::string key = key_name(entry.first, source_, path_);
      if (!read_.count(key)) fail(full(key.c_str()), "is not a known key");
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ConfigError(source_ + ": " + key + ": " + what);
  }

 private:
  YAML::Node find(const char* key) {
    read_.insert(key);
    if (!node_) return node_;  // undefined, like any missing key
    // Const access: operator[] on a non-const node would create the key.
    const YAML::Node& node = node_;
    return node[key];
  }
  std::string full(const char* key) const { return path_.empty() ? key : path_ + "." + key; }

  template <typename T>
  static std::string kind() {
    return std::is_integral<T>::value ? "an integer" : "a number";
  }
  template <typename T>
  static std::string range(T lo, T hi) {
    std::ostringstream out;
    out << "[" << lo << ", " << hi << "]";
    return out.str();
  }

  YAML::Node node_;
  std::string path_;
  std::string source_;
  std::set<std::string> read_;
};

void read_sensor(SectionReader& in, SensorParams& s) {
  in.text("name", s.name);
  in.number("rows", s.rows, 1, 512);
  in.number("columns", s.columns, 16, 20000);
  in.choice("row_source", s.row_source,
            {{"auto", RowSource::kAuto},
             {"ring", RowSource::kRing},
             {"elevation", RowSource::kElevation}});
  double vertical_min = -15.0, vertical_max = 15.0;
  in.number("vertical_min_deg", vertical_min, -90.0, 90.0);
  in.number("vertical_max_deg", vertical_max, -90.0, 90.0);
  in.list("beam_angles_deg", s.beam_angles_deg, -90.0, 90.0);
  in.list("beam_offsets_m", s.beam_offsets_m, -1.0, 1.0);
  in.list("ring_to_row", s.ring_to_row, -1, 511);
  in.number("min_range", s.min_range, 0.0, 50.0);
  in.number("max_range", s.max_range, 1.0, 1000.0);
  in.number("mount_angle_deg", s.mount_angle_deg, -90.0, 90.0);
  in.number("ground_rows", s.ground_rows, 0, 512);
  in.number("scan_period", s.scan_period, 0.001, 1.0);
  in.boolean("deskewed", s.deskewed);
  if (s.beam_angles_deg.empty()) {
    if (!(vertical_max > vertical_min)) {
      in.fail("sensor.vertical_max_deg", "must be greater than sensor.vertical_min_deg");
    }
    for (int row = 0; row < s.rows; ++row) {
      const double step = s.rows > 1 ? (vertical_max - vertical_min) / (s.rows - 1) : 0.0;
      s.beam_angles_deg.push_back(vertical_min + step * row);
    }
  } else if (in.has("vertical_min_deg") || in.has("vertical_max_deg")) {
    in.fail("sensor.beam_angles_deg", "give either beam_angles_deg or vertical_min/max_deg");
  }
  in.reject_unknown_keys();
}

void read_size_rule(SectionReader& in, ClusterSizeRule& rule) {
  in.number("min_cluster_points", rule.min_points, 1, 1000000);
  in.number("min_line_cluster_points", rule.min_points_multi_row, 1, 1000000);
  in.number("min_cluster_rows", rule.min_rows, 1, 512);
}

void read_segmentation(SectionReader& in, SegmentationParams& s) {
  in.number("beta0_deg", s.beta0_deg, 0.1, 89.9);
  read_size_rule(in, s.size_rule);
  in.number("ground_slope_tolerance_deg", s.ground_slope_tolerance_deg, 0.0, 45.0);
  in.number("ground_row_gap_deg", s.ground_row_gap_deg, 0.0, 10.0);
  in.number("ground_downsample", s.ground_downsample, 1, 100);
  in.number("outlier_downsample", s.outlier_downsample, 1, 100);
  in.reject_unknown_keys();
}

void read_ambient(SectionReader& in, AmbientFilterParams& a) {
  in.choice("mode", a.mode,
            {{"adaptive", Beta0Mode::kAdaptive},
             {"fixed", Beta0Mode::kFixed},
             {"none", Beta0Mode::kNone}});
  in.number("beta0_min_deg", a.beta0_min_deg, 0.1, 89.9);
  in.number("beta0_max_deg", a.beta0_max_deg, 0.1, 89.9);
  in.number("mu_strict_below", a.mu_strict_below, 0.0, 1.0);
  in.number("mu_lenient_above", a.mu_lenient_above, 0.0, 1.0);
  in.number("skeleton_beta0_deg", a.skeleton_beta0_deg, 0.1, 89.9);
  in.number("fixed_beta0_deg", a.fixed_beta0_deg, 0.1, 89.9);
  in.number("euclidean_window", a.euclidean_window, 1, 10);
  in.number("euclidean_gamma", a.euclidean_gamma, 0.1, 100.0);
  in.number("euclidean_fixed_threshold", a.euclidean_fixed_threshold, 0.0, 100.0);
  in.choice("euclidean_criterion", a.euclidean_criterion,
            {{"distance", EuclideanCriterion::kDistance},
             {"range_difference", EuclideanCriterion::kRangeDifference}});
  in.number("skeleton_euclidean_min_points", a.skeleton_euclidean_min_points, 1, 1000000);
  in.number("skeleton_depth_min_points", a.skeleton_depth_min_points, 1, 1000000);
  in.number("normal_sample_ratio", a.normal_sample_ratio, 0.0001, 1.0);
  in.number("normal_window", a.normal_window, 1, 10);
  in.number("normal_depth_threshold", a.normal_depth_threshold, 0.01, 100.0);
  in.number("normal_min_neighbors", a.normal_min_neighbors, 3, 1000);
  in.number("seed", a.seed, 0u, 4294967295u);
  in.number("mu_evidence_normals", a.mu_evidence_normals, 0, 1000000);
  in.number("mu_structure_weight", a.mu_structure_weight, 0.0, 10.0);
  in.number("mu_structure_reference", a.mu_structure_reference, 0.0, 1.0);
  in.number("fragment_smoothness_floor", a.fragment_smoothness_floor, 0.0, 1.0);
  in.number("fragment_smooth_tolerance_m", a.fragment_smooth_tolerance_m, 0.001, 10.0);
  in.number("mu_smoothing", a.mu_smoothing, 0.0, 0.99);
  in.number("mu_keep_every_cluster", a.mu_keep_every_cluster, 0.0, 2.0);
  if (a.beta0_min_deg > a.beta0_max_deg) {
    in.fail("ambient_filter.beta0_min_deg", "must not exceed ambient_filter.beta0_max_deg");
  }
  if (a.mu_strict_below >= a.mu_lenient_above) {
    in.fail("ambient_filter.mu_strict_below", "must be below ambient_filter.mu_lenient_above");
  }
  in.reject_unknown_keys();
}

void read_features(SectionReader& in, FeatureParams& f) {
  in.number("sectors", f.sectors, 1, 64);
  in.number("sharp_per_sector", f.sharp_per_sector, 0, 1000);
  in.number("less_sharp_per_sector", f.less_sharp_per_sector, 0, 10000);
  in.number("flat_per_sector", f.flat_per_sector, 0, 1000);
  in.number("edge_threshold", f.edge_threshold, 0.0, 100.0);
  in.number("surface_threshold", f.surface_threshold, 0.0, 100.0);
  in.number("occlusion_threshold", f.occlusion_threshold, 0.0, 100.0);
  in.number("parallel_threshold", f.parallel_threshold, 0.0, 1.0);
  in.number("less_flat_voxel", f.less_flat_voxel, 0.0, 10.0);
  if (f.less_sharp_per_sector < f.sharp_per_sector) {
    in.fail("features.less_sharp_per_sector", "must be at least features.sharp_per_sector");
  }
  in.reject_unknown_keys();
}

void read_odometry(SectionReader& in, OdometryParams& o) {
  in.choice("mode", o.mode,
            {{"two_step", OdometryMode::kTwoStep}, {"joint", OdometryMode::kJoint}});
  in.number("max_iterations", o.max_iterations, 1, 100);
  in.number("solver_iterations", o.solver_iterations, 1, 100);
  in.number("max_match_distance", o.max_match_distance, 0.1, 100.0);
  in.number("huber_loss", o.huber_loss, 0.001, 100.0);
  in.boolean("constant_velocity", o.constant_velocity);
  in.boolean("motion_from_mapping", o.motion_from_mapping);
  in.number("start_search_max_speed", o.start_search_max_speed, 0.0, 100.0);
  in.number("start_search_step", o.start_search_step, 0.05, 10.0);
  in.number("max_speed", o.max_speed, 0.0, 1000.0);
  in.number("max_turn_rate_deg", o.max_turn_rate_deg, 0.0, 36000.0);
  in.number("range_weight_fit_error", o.range_weight_fit_error, 0.0, 10.0);
  in.number("range_weight_noise", o.range_weight_noise, 0.001, 1.0);
  in.number("residual_sigma", o.residual_sigma, 1e-4, 10.0);
  in.number("follow_test_shift", o.follow_test_shift, 0.0, 10.0);
  in.number("follow_test_max", o.follow_test_max, 0.0, 10.0);
  in.number("follow_test_still_speed", o.follow_test_still_speed, 0.0, 100.0);
  in.reject_unknown_keys();
}

void read_mapping(SectionReader& in, MappingParams& m) {
  in.boolean("enabled", m.enabled);
  in.number("max_iterations", m.max_iterations, 1, 100);
  in.number("solver_iterations", m.solver_iterations, 1, 100);
  in.number("keep_correspondence_distance", m.keep_correspondence_distance, 0.0, 1.0);
  in.number("huber_loss", m.huber_loss, 0.001, 100.0);
  in.number("corner_voxel", m.corner_voxel, 0.01, 10.0);
  in.number("surface_voxel", m.surface_voxel, 0.01, 10.0);
  in.number("scan_corner_voxel", m.scan_corner_voxel, 0.0, 10.0);
  in.number("scan_surface_voxel", m.scan_surface_voxel, 0.0, 10.0);
  in.number("keyframe_distance", m.keyframe_distance, 0.0, 100.0);
  in.number("keyframe_angle_deg", m.keyframe_angle_deg, 0.0, 180.0);
  in.number("local_map_radius", m.local_map_radius, 1.0, 1000.0);
  in.number("local_map_keyframes", m.local_map_keyframes, 1, 10000);
  in.number("local_map_lag_keyframes", m.local_map_lag_keyframes, 0, 10000);
  in.number("keyframe_merge_group", m.keyframe_merge_group, 1, 1000);
  in.number("keyframe_merge_after", m.keyframe_merge_after, 1, 1000000);
  in.number("keyframe_merge_radius", m.keyframe_merge_radius, 0.0, 10000.0);
  if (m.keyframe_merge_group > 1 &&
      m.keyframe_merge_after < m.local_map_keyframes + m.local_map_lag_keyframes) {
    in.fail("mapping.keyframe_merge_after",
            "must be at least mapping.local_map_keyframes + mapping.local_map_lag_keyframes (" +
                std::to_string(m.local_map_keyframes + m.local_map_lag_keyframes) +
                "): the local map's keyframes are not merged");
  }
  in.number("degeneracy_eigenvalue", m.degeneracy_eigenvalue, 0.0, 1e9);
  in.number("residual_sigma", m.residual_sigma, 1e-4, 10.0);
  in.number("degenerate_translation_sigma", m.degenerate_translation_sigma, 1e-4, 1000.0);
  in.number("degenerate_rotation_sigma_deg", m.degenerate_rotation_sigma_deg, 1e-4, 180.0);
  in.number("gravity_sigma_deg", m.gravity_sigma_deg, 0.001, 90.0);
  in.number("weak_direction_prior", m.weak_direction_prior, 0.0, 1e6);
  in.number("vertical_prior_weight", m.vertical_prior_weight, 0.0, 1e6);
  in.number("vertical_prior_max_tilt_deg", m.vertical_prior_max_tilt_deg, 0.0, 45.0);
  in.number("max_motion_change", m.max_motion_change, 0.0, 100.0);
  in.number("max_motion_change_deg", m.max_motion_change_deg, 0.0, 180.0);
  in.number("max_gated_scans", m.max_gated_scans, 0, 1000);
  in.reject_unknown_keys();
}

void read_localization(SectionReader& in, LocalizationParams& l) {
  in.number("min_match_ratio", l.min_match_ratio, 0.0, 1.0);
  in.number("lost_after_scans", l.lost_after_scans, 1, 100000);
  in.number("search_radius", l.search_radius, 0.1, 10000.0);
  in.number("retry_period", l.retry_period, 0.0, 3600.0);
  in.number("recent_keyframes", l.recent_keyframes, 0, 10000);
  in.reject_unknown_keys();
}

void read_saved_map(SectionReader& in, SavedMapParams& m) {
  in.number("voxel_size", m.voxel_size, SavedMapParams::kMinVoxel, SavedMapParams::kMaxVoxel);
  in.reject_unknown_keys();
}

void read_loop_closure(SectionReader& in, LoopClosureParams& l) {
  in.boolean("enabled", l.enabled);
  in.number("search_radius", l.search_radius, 0.1, 1000.0);
  in.number("min_time_gap", l.min_time_gap, 0.0, 1.0e6);
  in.number("min_loop_path", l.min_loop_path, 0.0, 1.0e6);
  in.number("neighbourhood_keyframes", l.neighbourhood_keyframes, 0, 10000);
  in.boolean("place_recognition", l.place.enabled);
  in.number("place_rings", l.place.rings, 2, 200);
  in.number("place_sectors", l.place.sectors, 4, 720);
  in.number("place_max_radius", l.place.max_radius, 1.0, 1000.0);
  in.number("place_height_offset", l.place.height_offset, 0.0, 20.0);
  in.number("place_candidates", l.place.candidates, 1, 1000);
  in.number("place_max_distance", l.place.max_distance, 0.0, 1.0);
  in.number("place_max_ratio", l.place.max_ratio, 0.0, 1.0);
  in.number("place_elsewhere_distance", l.place.elsewhere_distance, 0.0, 10000.0);
  in.number("verify_radius", l.verify_radius, 1.0, 1000.0);
  in.number("inlier_distance", l.inlier_distance, 0.01, 100.0);
  in.number("min_inlier_ratio", l.min_inlier_ratio, 0.0, 1.0);
  in.number("max_inlier_mse", l.max_inlier_mse, 1.0e-6, 100.0);
  in.number("consistency_window", l.consistency_window, 1, 100000);
  in.number("consistency_translation", l.consistency_translation, 0.0, 100.0);
  in.number("consistency_rotation_deg", l.consistency_rotation_deg, 0.0, 180.0);
  in.number("max_drift_fraction", l.max_drift_fraction, 0.0, 1.0);
  in.number("max_drift_offset", l.max_drift_offset, 0.0, 10000.0);
  in.number("max_loop_residual", l.max_loop_residual, 0.1, 1.0e6);
  in.number("min_closure_interval", l.min_closure_interval, 0.0, 1.0e6);
  in.number("voxel_size", l.voxel_size, 0.0, 10.0);
  in.number("icp_max_correspondence_distance", l.icp_max_correspondence_distance, 0.01, 1000.0);
  in.number("icp_max_iterations", l.icp_max_iterations, 1, 10000);
  in.number("icp_max_points", l.icp_max_points, 3, 10000000);
  in.boolean("refine", l.refine);
  in.number("map_points_per_scan", l.map_points_per_scan, 1, 100000000);
  in.number("icp_iterations_per_scan", l.icp_iterations_per_scan, 1, 10000);
  in.number("graph_iterations_per_scan", l.graph_iterations_per_scan, 1, 10000);
  in.number("graph_max_nodes", l.graph_max_nodes, 10, 1000000);
  in.number("odometry_sigma_translation", l.odometry_sigma_translation, 1.0e-6, 100.0);
  in.number("odometry_sigma_rotation_deg", l.odometry_sigma_rotation_deg, 1.0e-6, 180.0);
  in.number("loop_sigma_translation", l.loop_sigma_translation, 1.0e-6, 100.0);
  in.number("loop_sigma_rotation_deg", l.loop_sigma_rotation_deg, 1.0e-6, 180.0);
  in.choice("robust_loss", l.robust_loss,
            {{"cauchy", RobustLoss::kCauchy},
             {"huber", RobustLoss::kHuber},
             {"none", RobustLoss::kNone}});
  in.number("robust_loss_scale", l.robust_loss_scale, 0.01, 1000.0);
  in.reject_unknown_keys();
}

// A list of exactly three numbers.
void read_triple(SectionReader& in, const char* key, std::vector<double>& values, double lo,
                 double hi, const std::string& section) {
  in.list(key, values, lo, hi);
  if (values.size() != 3) {
    in.fail(section + "." + key,
            "expected a list of three numbers, found " + std::to_string(values.size()));
  }
}

void read_imu(SectionReader& in, ImuParams& imu) {
  read_triple(in, "extrinsic_rpy_deg", imu.extrinsic_rpy_deg, -360.0, 360.0, "imu");
  read_triple(in, "extrinsic_xyz_m", imu.extrinsic_xyz_m, -100.0, 100.0, "imu");
  in.number("time_offset_s", imu.time_offset_s, -10.0, 10.0);
  in.number("gyro_noise_density", imu.gyro_noise_density, 1e-9, 1.0);
  in.number("accel_noise_density", imu.accel_noise_density, 1e-9, 10.0);
  in.number("gyro_bias_random_walk", imu.gyro_bias_random_walk, 0.0, 1.0);
  in.number("accel_bias_random_walk", imu.accel_bias_random_walk, 0.0, 10.0);
  in.number("gyro_bias_sigma", imu.gyro_bias_sigma, 1e-9, 1.0);
  in.number("accel_bias_sigma", imu.accel_bias_sigma, 1e-9, 10.0);
  in.number("gravity", imu.gravity, 9.7, 9.9);
  in.number("max_gap_s", imu.max_gap_s, 0.001, 10.0);
  in.number("max_angular_velocity", imu.max_angular_velocity, 0.1, 1000.0);
  in.number("max_acceleration", imu.max_acceleration, 1.0, 10000.0);
  in.reject_unknown_keys();
}

void read_wheel_odometry(SectionReader& in, WheelOdometryParams& wheel) {
  read_triple(in, "extrinsic_rpy_deg", wheel.extrinsic_rpy_deg, -360.0, 360.0, "wheel_odometry");
  read_triple(in, "extrinsic_xyz_m", wheel.extrinsic_xyz_m, -100.0, 100.0, "wheel_odometry");
  in.number("time_offset_s", wheel.time_offset_s, -10.0, 10.0);
  in.number("speed_sigma", wheel.speed_sigma, 1e-6, 100.0);
  in.number("yaw_rate_sigma_deg", wheel.yaw_rate_sigma_deg, 1e-6, 1000.0);
  in.number("max_gap_s", wheel.max_gap_s, 0.001, 10.0);
  in.number("max_speed", wheel.max_speed, 0.1, 1000.0);
  in.number("max_yaw_rate_deg", wheel.max_yaw_rate_deg, 0.1, 36000.0);
  in.reject_unknown_keys();
}

// The per-scan settings, given for kReferenceScanPeriod, at the sensor's period: the same per
// second. At the reference period nothing changes (not even by a rounding).
void hold_per_second(Config& config) {
  const double period = config.sensor.scan_period;
  if (period == kReferenceScanPeriod) return;
  const double scans = period / kReferenceScanPeriod;  // reference scans in one of this sensor's
  const auto count = [scans](int reference) {
    return reference > 0 ? std::max(1, static_cast<int>(std::lround(reference / scans))) : 0;
  };
  MappingParams& m = config.mapping;
  m.max_motion_change *= scans;
  m.max_motion_change_deg *= scans;
  m.max_gated_scans = count(m.max_gated_scans);
  config.localization.lost_after_scans = count(config.localization.lost_after_scans);
  config.ambient.mu_smoothing = std::pow(config.ambient.mu_smoothing, scans);
}

void read_clustering_benchmark(SectionReader& in, ClusteringBenchmarkParams& b) {
  in.number("min_cluster_points", b.min_cluster_points, 1, 1000000);
  in.reject_unknown_keys();
}

}  // namespace

void validate(const SensorParams& s, const std::string& source) {
  auto fail = [&](const std::string& key, const std::string& what) {
    throw ConfigError(source + ": " + key + ": " + what);
  };
  if (static_cast<int>(s.beam_angles_deg.size()) != s.rows) {
    fail("sensor.beam_angles_deg", "has " + std::to_string(s.beam_angles_deg.size()) +
                                       " entries, expected one per row (" + std::to_string(s.rows) +
                                       ")");
  }
  for (int row = 1; row < s.rows; ++row) {
    if (!(s.beam_angles_deg[row] > s.beam_angles_deg[row - 1])) {
      fail("sensor.beam_angles_deg", "must be strictly ascending (row 0 = lowest beam); entry " +
                                         std::to_string(row) + " is not above entry " +
                                         std::to_string(row - 1));
    }
  }
  if (!s.beam_offsets_m.empty() && static_cast<int>(s.beam_offsets_m.size()) != s.rows) {
    fail("sensor.beam_offsets_m", "has " + std::to_string(s.beam_offsets_m.size()) +
                                      " entries, expected none or one per row (" +
                                      std::to_string(s.rows) + ")");
  }
  for (std::size_t ring = 0; ring < s.ring_to_row.size(); ++ring) {
    if (s.ring_to_row[ring] >= s.rows) {
      fail("sensor.ring_to_row[" + std::to_string(ring) + "]",
           "expected a row in [0, " + std::to_string(s.rows - 1) + "]");
    }
  }
  if (!(s.max_range > s.min_range)) fail("sensor.max_range", "must exceed sensor.min_range");
  if (s.ground_rows > s.rows) {
    fail("sensor.ground_rows", "expected an integer in [0, " + std::to_string(s.rows) + "]");
  }
}

namespace {

YAML::Node parse_sections(const std::string& yaml_text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": not valid YAML: " + e.what());
  }
  if (!root || root.IsNull()) throw ConfigError(source + ": empty config");
  if (!root.IsMap()) throw ConfigError(source + ": expected a mapping of sections");
  return root;
}

std::string read_text(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw ConfigError(path + ": cannot open config file");
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

Config config_from(const YAML::Node& root, const std::string& source);

}  // namespace

Config parse_config(const std::string& yaml_text, const std::string& source) {
  return config_from(parse_sections(yaml_text, source), source);
}

Config load_config(const std::string& path) {
  return parse_config(read_text(path), path);
}

Config load_config(const std::vector<std::string>& paths) {
  if (paths.empty()) throw ConfigError("no config file given");
  YAML::Node merged = parse_sections(read_text(paths.front()), paths.front());
  std::string source = paths.front();
  for (std::size_t i = 1; i < paths.size(); ++i) {
    const YAML::Node overlay = parse_sections(read_text(paths[i]), paths[i]);
    for (const auto& section : overlay) {
      const std::string name = key_name(section.first, paths[i], "(top level)");
      if (!section.second.IsMap() || !merged[name] || !merged[name].IsMap()) {
        merged[name] = section.second;
        continue;
      }
      YAML::Node target = merged[name];
      for (const auto& entry : section.second)
        target[key_name(entry.first, paths[i], name)] = entry.second;
    }
    source += " + " + paths[i];
  }
  return config_from(merged, source);
}

namespace {

Config config_from(const YAML::Node& root, const std::string& source) {
  Config config;
  config.source = source;
  const YAML::Node& sections = root;  // const: looking a section up must not create it
  auto section = [&](const char* name) { return SectionReader(sections[name], name, source); };
  if (!sections["sensor"]) throw ConfigError(source + ": sensor: missing section");
  SectionReader sensor = section("sensor");
  read_sensor(sensor, config.sensor);
  SectionReader segmentation = section("segmentation");
  read_segmentation(segmentation, config.segmentation);
  SectionReader ambient = section("ambient_filter");
  read_ambient(ambient, config.ambient);
  SectionReader features = section("features");
  read_features(features, config.features);
  SectionReader odometry = section("odometry");
  read_odometry(odometry, config.odometry);
  SectionReader mapping = section("mapping");
  read_mapping(mapping, config.mapping);
  SectionReader loop_closure = section("loop_closure");
  read_loop_closure(loop_closure, config.loop_closure);
  SectionReader localization = section("localization");
  read_localization(localization, config.localization);
  SectionReader saved_map = section("saved_map");
  read_saved_map(saved_map, config.saved_map);
  SectionReader benchmark = section("clustering_benchmark");
  read_clustering_benchmark(benchmark, config.clustering_benchmark);
  SectionReader imu = section("imu");
  read_imu(imu, config.imu);
  SectionReader wheel_odometry = section("wheel_odometry");
  read_wheel_odometry(wheel_odometry, config.wheel_odometry);

  for (const auto& entry : root) {
    const std::string name = key_name(entry.first, source, "(top level)");
    static const std::set<std::string> known = {
        "sensor",  "segmentation",  "ambient_filter", "features",  "odometry",
        "mapping", "loop_closure",  "localization",   "saved_map", "clustering_benchmark",
        "imu",     "wheel_odometry"};
    if (!known.count(name)) throw ConfigError(source + ": " + name + ": is not a known section");
  }
  validate(config.sensor, source);
  hold_per_second(config);
  return config;
}

}  // namespace

}  // namespace adaptive_lego_loam
