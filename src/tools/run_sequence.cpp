// Runs the whole pipeline over a sequence (KITTI folder, PCD folder or bag) and writes the poses
// (KITTI and TUM), per-frame stage times, the ambient filter's output and a summary; optionally
// saves the map, or localizes on a saved one. Every output is written under a temporary name and
// put in place only when the run succeeds: a failed run leaves an earlier run's files as they were.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <optional>

#include "adaptive_lego_loam/core/common/scan_stamps.h"
#include "adaptive_lego_loam/core/odometry/observability.h"
#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/core/projection/config_fit.h"
#include "adaptive_lego_loam/io/atomic_files.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/map_files.h"
#include "adaptive_lego_loam/io/motion_sensor_files.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/process_memory.h"
#include "adaptive_lego_loam/io/progress.h"
#include "adaptive_lego_loam/io/scan_sequence.h"
#include "adaptive_lego_loam/ros/bag_sequence.h"
#include "adaptive_lego_loam/ros/motion_sensor_conversions.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;
namespace fs = std::filesystem;

namespace {

// The columns of timing.csv, in pipeline order; stages a frame did not run are 0.
const std::vector<std::string> kStages = {
    "projection",       "ground",          "euclidean_clustering",
    "skeleton",         "normals",         "degeneration",
    "depth_clustering", "segmented_cloud", "motion_sensors",
    "deskew",           "features",        "odometry",
    "local_map",        "mapping",         "keyframes",
    "loop_closure"};

struct Options {
  std::vector<std::string> config;
  std::string input, topic, output;
  double beta0 = -1.0;
  bool adaptive = false;
  bool no_segmentation = false;
  int max_frames = -1;
  bool cpu_time = false;
  bool skip_bad_scans = false;
  int threads = 1;
  std::string save_map, localize;
  std::vector<double> initial_pose;  // x, y, z, yaw in degrees
  std::string imu, wheel_odom, imu_topic, wheel_odom_topic;
};

// The optional motion sensors' samples, from CSV files or the bag, handed to the pipeline in
// their order up to each scan's stamp (on the scans' clock: the config's time offsets applied),
// as a node hands them over before it processes the scan. A fault is logged once per input and
// kind; all are counted in summary.json.
class MotionSensorFeed {
 public:
  MotionSensorFeed(const Options& options, const Config& config)
      : imu_offset_(config.imu.time_offset_s), wheel_offset_(config.wheel_odometry.time_offset_s) {
    if (!options.imu.empty()) imu_ = read_imu_csv(options.imu);
    if (!options.imu_topic.empty())
      imu_ = ros_bridge::read_bag_imu(options.input, options.imu_topic);
    if (!options.wheel_odom.empty()) wheel_ = read_wheel_odometry_csv(options.wheel_odom);
    if (!options.wheel_odom_topic.empty()) {
      wheel_ = ros_bridge::read_bag_wheel_odometry(options.input, options.wheel_odom_topic);
    }
  }

  std::string describe() const {
    std::string text;
    if (!imu_.empty()) text += ", IMU " + std::to_string(imu_.size()) + " samples";
    if (!wheel_.empty()) text += ", wheel odometry " + std::to_string(wheel_.size()) + " samples";
    return text;
  }

  void feed_until(double stamp, Pipeline& pipeline) {
    for (; next_imu_ < imu_.size() && imu_[next_imu_].stamp + imu_offset_ <= stamp; ++next_imu_) {
      report("IMU", imu_[next_imu_].stamp, pipeline.add_imu(imu_[next_imu_]), imu_reported_);
    }
    for (; next_wheel_ < wheel_.size() && wheel_[next_wheel_].stamp + wheel_offset_ <= stamp;
         ++next_wheel_) {
      report("wheel odometry", wheel_[next_wheel_].stamp,
             pipeline.add_wheel_odometry(wheel_[next_wheel_]), wheel_reported_);
    }
  }

 private:
  static void report(const char* input, double stamp, std::optional<SampleFault> fault,
                     std::array<bool, kSampleFaultKinds>& reported) {
    if (!fault || reported[static_cast<int>(*fault)]) return;
    reported[static_cast<int>(*fault)] = true;
    std::fprintf(stderr,
                 "\nrun_sequence: warning: %s sample at %.6f s dropped: %s (further ones are "
                 "counted in summary.json)\n",
                 input, stamp, to_string(*fault));
  }

  double imu_offset_, wheel_offset_;
  std::vector<ImuSample> imu_;
  std::vector<WheelOdometrySample> wheel_;
  std::size_t next_imu_ = 0, next_wheel_ = 0;
  std::array<bool, kSampleFaultKinds> imu_reported_{}, wheel_reported_{};
};

nlohmann::json input_status(const InputStatus& input) {
  nlohmann::json faults;
  for (int kind = 0; kind < kSampleFaultKinds; ++kind)
    faults[to_string(static_cast<SampleFault>(kind))] = input.faults[kind];
  return {{"accepted", input.accepted},
          {"dropped", input.dropped()},
          {"faults", faults},
          {"gaps", input.gaps},
          {"latest_gap_s", input.latest_gap_s},
          {"rate_hz", input.rate_hz}};
}

nlohmann::json motion_sensors_summary(const MotionSensorsStatus& status) {
  nlohmann::json summary;
  if (status.imu.accepted + status.imu.dropped() > 0) {
    summary["imu"] = input_status(status.imu);
    summary["imu"]["scans_used"] = status.imu_scans;
    summary["imu"]["scans_lidar_only"] = status.imu_fallbacks;
    summary["imu"]["restarts"] = status.imu_restarts;
    summary["imu"]["lidar_motions_refused"] = status.lidar_rejections;
    summary["imu"]["gyro_bias_rad_s"] = {status.gyro_bias.x(), status.gyro_bias.y(),
                                         status.gyro_bias.z()};
    summary["imu"]["accel_bias_m_s2"] = {status.accel_bias.x(), status.accel_bias.y(),
                                         status.accel_bias.z()};
  }
  if (status.wheel.accepted + status.wheel.dropped() > 0) {
    summary["wheel_odometry"] = input_status(status.wheel);
    summary["wheel_odometry"]["scans_used"] = status.wheel_scans;
    summary["wheel_odometry"]["scans_lidar_only"] = status.wheel_fallbacks;
    summary["wheel_odometry"]["slips"] = status.wheel_slips;
    summary["wheel_odometry"]["scale"] = status.wheel_scale;
    summary["wheel_odometry"]["scale_sigma"] = status.wheel_scale_sigma;
  }
  return summary;
}

std::unique_ptr<ScanSequence> open_sequence(const Options& options, const SensorParams& sensor) {
  if (fs::is_directory(options.input)) {
    return open_folder_sequence(options.input, sensor.scan_period);
  }
  if (fs::path(options.input).extension() == ".bag") {
    return ros_bridge::open_bag_sequence(options.input, options.topic, {sensor.scan_period});
  }
  throw IoError(options.input +
                ": expected a KITTI sequence folder, a folder of .bin/.pcd scans "
                "or a .bag file");
}

class Outputs {
 public:
  explicit Outputs(const std::string& dir)
      : dir_(dir),
        timing_(prepared(dir, "timing.csv")),
        degeneration_(path("degeneration.csv")),
        loops_(path("loops.csv")),
        localization_(path("localization.csv")) {
    loops_.stream()
        << "frame,current_keyframe,matched_keyframe,current_frame,matched_frame,"
           "source,status,inlier_ratio,inlier_mse,fitness,refinement_m,relative_x,relative_y,"
           "relative_z,relative_yaw_deg,closed\n";
    std::ofstream& timing = timing_.stream();
    timing << "frame";
    for (const auto& stage : kStages)
      timing << "," << stage;
    timing << ",total,rss_mb,heap_mb\n";
    degeneration_.stream() << "frame,mu,beta0_deg,direction_x,direction_y,skeleton_points,"
                              "normals,valid,map_degenerate_directions,euclidean_points,"
                              "fragment_smoothness,structure_share,every_cluster_kept,"
                              "map_weak_sigma_m,map_weak_x,map_weak_y,map_weak_z,"
                              "map_rotation_sigma_deg,estimate_weak_sigma_m,estimate_weak_x,"
                              "estimate_weak_y,estimate_weak_z,motion_prior,lidar_weak_sigma_m,"
                              "degenerate,matched"
                           << covariance_header()
                           << ",odometry_weak_sigma_m,odometry_weak_x,odometry_weak_y,"
                              "odometry_weak_z\n";
    localization_.stream() << "frame,state,match_ratio,alignment,inlier_ratio,inlier_mse\n";
  }

  // Puts the streamed files in place (the run succeeded).
  void commit(bool localizing) {
    timing_.commit();
    degeneration_.commit();
    loops_.commit();
    if (localizing) localization_.commit();
  }

  void add_localization(int frame, const std::optional<LocalizationStatus>& status) {
    if (!status) return;
    std::ofstream& out = localization_.stream();
    out << frame << "," << to_string(status->state) << "," << status->match_ratio << ",";
    if (status->alignment) {
      const LoopDetection& alignment = *status->alignment;
      out << (alignment.accepted() ? "accepted" : to_string(alignment.status)) << ","
          << alignment.inlier_ratio << "," << alignment.inlier_mse;
    } else {
      out << ",,";
    }
    out << "\n";
  }

  std::string path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

  // A loop-closure attempt that finished on a scan, or loops that entered the graph on it.
  void add_loop(int frame, const std::optional<LoopDetection>& loop, bool closed,
                const std::vector<Keyframe>& keyframes) {
    if (!loop && !closed) return;
    std::ofstream& loops_out = loops_.stream();
    loops_out << frame << ",";
    if (loop) {
      const auto frame_of = [&](int keyframe) {
        return keyframe >= 0 ? std::to_string(keyframes.at(keyframe).frame) : std::string();
      };
      const Eigen::Isometry3d& relative = loop->relative_pose;
      loops_out << loop->current_index << "," << loop->matched_index << ","
                << frame_of(loop->current_index) << "," << frame_of(loop->matched_index) << ","
                << (loop->source == CandidateSource::kPlace ? "place" : "radius") << ","
                << (loop->accepted() ? "verified" : to_string(loop->status)) << ","
                << loop->inlier_ratio << "," << loop->inlier_mse << "," << loop->fitness << ","
                << loop->refinement_m << "," << relative.translation().x() << ","
                << relative.translation().y() << "," << relative.translation().z() << ","
                << std::atan2(relative(1, 0), relative(0, 0)) * 180.0 / M_PI;
    } else {
      loops_out << ",,,,,,,,,,,,,,";
    }
    loops_out << "," << int(closed) << "\n";
  }

  void add(const FrameResult& frame, const AmbientFilterResult& filtered,
           const MappingParams& mapping) {
    std::ofstream& timing = timing_.stream();
    timing << frame.frame;
    for (const auto& stage : kStages)
      timing << "," << frame.times.get(stage);
    timing << "," << frame.times.total() << "," << resident_memory_mb() << "," << heap_in_use_mb()
           << "\n";
    const Degeneration& d = filtered.degeneration;
    degeneration_.stream() << frame.frame << "," << filtered.mu << "," << filtered.beta0_deg << ","
                           << d.weak_direction.x() << "," << d.weak_direction.y() << ","
                           << filtered.skeleton_points << "," << d.normals << "," << int(d.valid)
                           << "," << frame.mapping.degenerate_directions << ","
                           << filtered.euclidean_points << "," << filtered.fragment_smoothness
                           << "," << filtered.structure_share << ","
                           << int(filtered.every_cluster_kept);
    const Observability seen = observability(frame.mapping.information);
    degeneration_.stream() << "," << seen.weakest_sigma() << "," << seen.weakest_direction().x()
                           << "," << seen.weakest_direction().y() << ","
                           << seen.weakest_direction().z() << ","
                           << seen.rotation_sigma(0) * 180.0 / M_PI;
    // The estimate's: the correspondences' along the scene's weak direction as much as the scene
    // constrains it, and what the motion sensors' priors held.
    const Observability known =
        observability(pose_information(frame.mapping, scene_degeneration(filtered)));
    degeneration_.stream() << "," << known.weakest_sigma() << "," << known.weakest_direction().x()
                           << "," << known.weakest_direction().y() << ","
                           << known.weakest_direction().z() << ","
                           << int(frame.mapping.motion_prior);
    add_flag_and_covariance(frame, scene_degeneration(filtered), mapping);
    add_odometry(frame);
    stamps.push_back(frame.stamp);
    for (const auto& [stage, ms] : frame.times.entries())
      stage_ms[stage].push_back(ms);
    total_ms.push_back(frame.times.total());
  }

  std::vector<double> stamps;
  std::map<std::string, std::vector<double>> stage_ms;
  std::vector<double> total_ms;

 private:
  bool first_frame_ = true;
  // covariance_00 ... covariance_55: the published pose covariance's entries, row by row.
  static std::string covariance_header() {
    std::string header;
    for (int row = 0; row < 6; ++row)
      for (int column = 0; column < 6; ++column)
        header += ",covariance_" + std::to_string(row) + std::to_string(column);
    return header;
  }

  // The degenerate flag as map_optimization raises it (its weakest direction's sigma), whether the
  // scan matched the map, and the covariance published with the mapped pose (as
  // map_optimization's on /aft_mapped_to_init): what evaluate_odometry scores against the truth.
  void add_flag_and_covariance(const FrameResult& frame,
                               const std::optional<SceneDegeneration>& scene,
                               const MappingParams& mapping) {
    std::ofstream& out = degeneration_.stream();
    const WeakestDirection weakest = weakest_direction(frame.mapping, scene, mapping);
    out << "," << weakest.sigma << "," << int(weakest.degenerate) << ","
        << int(frame.mapping.matched);
    // The first scan starts the map (zero covariance) unless a saved map is localized on.
    const Matrix6d covariance =
        mapped_pose_covariance(frame.mapping, first_frame_ && !frame.localization, scene);
    first_frame_ = false;
    // Every digit: along a free direction the variance is 1e4 m^2 beside 1e-6 m^2 along the
    // fixed ones, and the scoring inverts it.
    char entry[32];
    for (int row = 0; row < 6; ++row) {
      for (int column = 0; column < 6; ++column) {
        std::snprintf(entry, sizeof(entry), ",%.17g", covariance(row, column));
        out << entry;
      }
    }
  }

  // The scan-to-scan registration's weakest translation direction and its sigma
  // (OdometryResult::information: not discounted along the scene's weak direction); infinite
  // when the scan was not registered.
  void add_odometry(const FrameResult& frame) {
    const Observability seen =
        observability(frame.odometry.registered ? frame.odometry.information : Matrix6d::Zero());
    degeneration_.stream() << "," << seen.weakest_sigma() << "," << seen.weakest_direction().x()
                           << "," << seen.weakest_direction().y() << ","
                           << seen.weakest_direction().z() << "\n";
  }

  // The folder made first: the files' temporaries go beside their places.
  static std::string prepared(const std::string& dir, const std::string& name) {
    std::error_code error;
    fs::create_directories(dir, error);
    if (error) throw IoError(dir + ": cannot create the output folder: " + error.message());
    return (fs::path(dir) / name).string();
  }

  std::string dir_;
  AtomicFile timing_, degeneration_, loops_, localization_;
};

// Nearest rank: the smallest value with at least that share of the values at or below it.
std::size_t percentile_rank(std::size_t count, double share) {
  const auto rank = static_cast<std::size_t>(std::ceil(share * count));
  return std::clamp<std::size_t>(rank, 1, count) - 1;
}

nlohmann::json statistics(std::vector<double> values) {
  if (values.empty()) return nullptr;
  std::sort(values.begin(), values.end());
  double sum = 0.0;
  for (double v : values)
    sum += v;
  return {{"mean", sum / values.size()},
          {"median", values[values.size() / 2]},
          {"p95", values[percentile_rank(values.size(), 0.95)]},
          {"max", values.back()}};
}

// The pose files, staged in `batch` (put in place with the other outputs).
void write_poses(const Options& options, const Pipeline& pipeline, const Outputs& outputs,
                 AtomicBatch& batch) {
  const std::vector<Eigen::Isometry3d> poses = pipeline.trajectory();
  batch.add(outputs.path("poses_kitti.txt"),
            [&](const std::string& path) { write_kitti_poses(path, poses); });
  batch.add(outputs.path("poses_tum.txt"),
            [&](const std::string& path) { write_tum_poses(path, outputs.stamps, poses); });
  // KITTI's ground truth is in the left camera's frame: with a calib.txt beside the scans, also
  // write the poses there (camera pose = Tr * lidar pose * Tr^-1).
  if (const auto calib = kitti_calib_beside(options.input)) {
    const Eigen::Isometry3d tr = read_kitti_calib_tr(*calib);
    std::vector<Eigen::Isometry3d> camera;
    for (const auto& pose : poses)
      camera.push_back(tr * pose * tr.inverse());
    batch.add(outputs.path("poses_camera.txt"),
              [&](const std::string& path) { write_kitti_poses(path, camera); });
  }
}

std::unique_ptr<Pipeline> make_pipeline(const Options& options, const Config& config) {
  if (options.localize.empty()) return std::make_unique<Pipeline>(config);
  SavedMap map = load_map(options.localize);
  if (!map.description.sensor.empty() && map.description.sensor != config.sensor.name) {
    std::fprintf(stderr, "run_sequence: warning: the map %s was made with sensor %s, not %s\n",
                 options.localize.c_str(), map.description.sensor.c_str(),
                 config.sensor.name.c_str());
  }
  std::fprintf(stderr, "run_sequence: localizing on %s (%zu keyframes)\n", options.localize.c_str(),
               map.keyframes.size());
  return std::make_unique<Pipeline>(
      config, std::move(map.keyframes),
      options.initial_pose.empty()
          ? Eigen::Isometry3d::Identity()
          : initial_pose(options.initial_pose[0], options.initial_pose[1], options.initial_pose[2],
                         options.initial_pose[3]));
}

// What localization did over the run.
struct LocalizationCounts {
  int tracked = 0, lost = 0, aligning = 0, alignments = 0, accepted = 0;
  void add(const std::optional<LocalizationStatus>& status) {
    if (!status) return;
    tracked += status->state == LocalizationState::kTracking;
    lost += status->state == LocalizationState::kLost;
    aligning += status->state == LocalizationState::kAligning;
    alignments += status->alignment.has_value();
    accepted += status->alignment && status->alignment->accepted();
  }
};

// The stand-in for a scan that could not be read (--skip-bad-scans): no points, so the pipeline
// predicts its pose and the poses stay one a frame. Its stamp is the one the sequence knows for
// it (times.txt, the bag), else a period after the last scan's.
Scan skipped_scan(const ScanSequence& sequence, std::optional<double> last_stamp,
                  double scan_period) {
  Scan scan;
  if (sequence.last_stamp()) {
    scan.stamp = *sequence.last_stamp();
  } else if (last_stamp) {
    scan.stamp = *last_stamp + scan_period;
  }
  return scan;
}

// The scans in order (at most --max-frames). Reading ahead (with threads), the scan after the one
// taken is read already (its ambient filter runs while this one is registered) and the one after
// that on a thread of its own. A scan that cannot be read stops the run when its turn comes, or
// with --skip-bad-scans is replaced by an empty one at its predicted stamp.
class ScanReader {
 public:
  ScanReader(ScanSequence& sequence, const Options& options, double scan_period, bool ahead)
      : sequence_(sequence),
        skip_bad_scans_(options.skip_bad_scans),
        scan_period_(scan_period),
        ahead_(ahead),
        limit_(options.max_frames) {}
  ~ScanReader() { join(); }

  // The next scan to process (nullptr: none is left); valid until the call after next.
  const Scan* take() {
    const int index = taken_++;
    const Scan* scan = scan_at(index);
    next_ = nullptr;
    if (scan && ahead_) {
      next_ = scan_at(index + 1, false);
      if (next_ && may_read(index + 2)) {
        reading_ = std::async(std::launch::async, [this] { read(); });
      }
    }
    return scan;
  }
  // With reading ahead, the scan the next take() returns (nullptr: none, or not reading ahead).
  const Scan* next() const { return next_; }
  // Once no read is running any more.
  int skipped() {
    join();
    return skipped_;
  }

 private:
  static constexpr int kSlots = 3;

  bool may_read(int index) const { return limit_ < 0 || index < limit_; }

  // Scan `index` (read now unless it was read ahead), nullptr past the end. A scan that could
  // not be read throws its error when `taking` it, else is nullptr until then.
  const Scan* scan_at(int index, bool taking = true) {
    if (!may_read(index)) return nullptr;
    join();
    while (reads_ <= index)
      read();
    const int slot = index % kSlots;
    if (errors_[slot]) {
      if (taking) std::rethrow_exception(errors_[slot]);
      return nullptr;
    }
    return slots_[slot] ? &*slots_[slot] : nullptr;
  }

  void join() {
    if (reading_.valid()) reading_.get();
  }

  void read() {
    const int slot = reads_ % kSlots;
    slots_[slot].reset();
    errors_[slot] = nullptr;
    try {
      try {
        slots_[slot] = sequence_.next();
      } catch (const IoError& e) {
        if (!skip_bad_scans_) throw;
        std::fprintf(stderr, "\nrun_sequence: warning: frame %d skipped: %s\n", reads_, e.what());
        ++skipped_;
        slots_[slot] = skipped_scan(sequence_, last_stamp_, scan_period_);
      }
    } catch (...) {
      errors_[slot] = std::current_exception();
    }
    if (slots_[slot]) last_stamp_ = slots_[slot]->stamp;
    ++reads_;
  }

  ScanSequence& sequence_;
  bool skip_bad_scans_;
  double scan_period_;
  bool ahead_;
  int limit_;  // -1: none
  std::optional<Scan> slots_[kSlots];
  std::exception_ptr errors_[kSlots];
  std::optional<double> last_stamp_;
  std::future<void> reading_;
  const Scan* next_ = nullptr;
  int taken_ = 0, reads_ = 0, skipped_ = 0;
};

std::string describe_segmentation(const AmbientFilterParams& ambient) {
  switch (ambient.mode) {
    case Beta0Mode::kAdaptive:
      return "adaptive beta0";
    case Beta0Mode::kFixed:
      return "fixed beta0 " + std::to_string(ambient.fixed_beta0_deg);
    case Beta0Mode::kNone:
      return "no segmentation";
  }
  return "";
}

int run(const Options& options) {
  Config config = load_config(options.config);
  if (options.beta0 > 0.0) {
    config.ambient.mode = Beta0Mode::kFixed;
    config.ambient.fixed_beta0_deg = options.beta0;
  } else if (options.adaptive) {
    config.ambient.mode = Beta0Mode::kAdaptive;
  } else if (options.no_segmentation) {
    config.ambient.mode = Beta0Mode::kNone;
  }
  // A map folder that cannot take the map stops the run now, not after it.
  if (!options.save_map.empty()) check_map_folder(options.save_map);
  std::unique_ptr<ScanSequence> sequence = open_sequence(options, config.sensor);
  MotionSensorFeed motion_sensors(options, config);
  std::unique_ptr<Pipeline> pipeline = make_pipeline(options, config);
  pipeline->set_threads(options.threads);
  Outputs outputs(options.output);
  const int total = options.max_frames >= 0 && sequence->size() >= 0
                        ? std::min(options.max_frames, sequence->size())
                        : sequence->size();
  std::fprintf(stderr, "run_sequence: %s%s, config %s, %s\n", sequence->describe().c_str(),
               motion_sensors.describe().c_str(), config.source.c_str(),
               describe_segmentation(config.ambient).c_str());
  ProgressBar progress("run_sequence", total);
  HeapTrimmer heap_trimmer;
  Stopwatch wall(Clock::kWall);
  int frames = 0, empty_scans = 0, motion_gated_scans = 0, skipped_scans = 0;
  int odometry_rejected_motions = 0;
  int odometry_held_scans = 0;
  ScanStamps stamps(config.sensor.scan_period);
  ConfigFitWarning fit(config.source, options.input);
  LocalizationCounts localization;
  std::string failure;
  ScanReader reader(*sequence, options, config.sensor.scan_period, pipeline->threads() > 1);
  try {
    // The reader stops at --max-frames.
    while (const Scan* scan = reader.take()) {
      stamps.add(scan->stamp);
      motion_sensors.feed_until(scan->stamp, *pipeline);
      const FrameResult& result = pipeline->process(*scan, reader.next());
      if (const auto warning =
              fit.check(config.sensor, pipeline->filter_result().segmentation.image,
                        rows_from_ring(config.sensor, scan->has_ring))) {
        std::fprintf(stderr, "\nrun_sequence: warning: %s\n", warning->c_str());
      }
      heap_trimmer.after_scan();
      empty_scans += !result.valid_scan;
      motion_gated_scans += result.motion_gated;
      odometry_rejected_motions += result.odometry.rejected;
      odometry_held_scans += result.odometry.held_direction.has_value();
      localization.add(result.localization);
      outputs.add(result, pipeline->filter_result(), config.mapping);
      outputs.add_loop(result.frame, result.loop, result.loop_closed, pipeline->keyframes());
      outputs.add_localization(result.frame, result.localization);
      progress.update(++frames);
    }
  } catch (const std::exception& e) {
    failure = e.what();
    pipeline.reset();  // before the reader: a scan filtered ahead is read until it is joined
  }
  skipped_scans = reader.skipped();
  progress.finish();
  if (!failure.empty()) {
    throw std::runtime_error(failure + " (after " + std::to_string(frames) +
                             " frames; nothing written, earlier outputs in " + options.output +
                             " are as they were)");
  }
  if (frames == 0) throw IoError(options.input + ": no scans");
  // A loop closure still running at the end of the input finishes now, outside every scan's
  // time: the online mapping would finish it over the next scans.
  nlohmann::json final_loop_closure;
  {
    const Stopwatch stopwatch;
    if (const std::optional<LoopDetection> loop = pipeline->finish_loop_closure()) {
      final_loop_closure = {{"status", to_string(loop->status)},
                            {"fitness", loop->fitness},
                            {"ms", stopwatch.elapsed_ms()}};
    }
  }
  const double wall_s = wall.elapsed_ms() / 1000.0;
  // The map first: when it cannot be saved, no output of this run takes the place of an earlier
  // one's. The files follow together once all are written.
  if (!options.save_map.empty()) {
    const MapDescription description{fs::absolute(options.config.front()).string(),
                                     config.sensor.name, "run_sequence", frames};
    save_map(options.save_map, pipeline->keyframes(), description, config);
    std::fprintf(stderr, "run_sequence: map saved in %s\n", options.save_map.c_str());
  }
  AtomicBatch batch;
  write_poses(options, *pipeline, outputs, batch);

  nlohmann::json summary;
  summary["input"] = options.input;
  summary["config"] = options.config;
  summary["beta0_mode"] = to_string(config.ambient.mode);
  if (config.ambient.mode == Beta0Mode::kFixed)
    summary["beta0_deg"] = config.ambient.fixed_beta0_deg;
  summary["frames"] = frames;
  summary["scans_without_valid_points"] = empty_scans;
  summary["skipped_scans"] = skipped_scans;
  summary["config_fit"] = fit.seen();  // what of the config does not fit the scans (empty: all)
  summary["input_stamps"] = {{"gaps", stamps.gaps()},
                             {"missing_scans", stamps.missing()},
                             {"duplicates", stamps.duplicates()},
                             {"backward_jumps", stamps.backward_jumps()}};
  summary["keyframes"] = pipeline->keyframes().size();
  summary["loops_closed"] = pipeline->mapping().loops_closed();
  const LoopClosureCounts& loops = pipeline->mapping().loop_closure_counts();
  summary["loop_closure"] = {{"place_candidates", loops.place_candidates},
                             {"radius_candidates", loops.radius_candidates},
                             {"verified", loops.verified},
                             {"rejected", loops.rejected},
                             {"beyond_drift_bound", loops.beyond_drift},
                             {"unconfirmed", loops.unconfirmed},
                             {"closed", loops.closed},
                             {"removed", loops.removed}};
  if (!final_loop_closure.is_null()) summary["loop_closure_after_last_scan"] = final_loop_closure;
  if (!options.localize.empty()) {
    summary["localization"] = {{"map", options.localize},
                               {"tracked_scans", localization.tracked},
                               {"lost_scans", localization.lost},
                               {"aligning_scans", localization.aligning},
                               {"alignments", localization.alignments},
                               {"accepted_alignments", localization.accepted}};
  }
  if (!options.save_map.empty()) summary["saved_map"] = options.save_map;
  const nlohmann::json sensors = motion_sensors_summary(pipeline->motion_sensors().status());
  if (!sensors.is_null()) summary["motion_sensors"] = sensors;
  summary["motion_gated_scans"] = motion_gated_scans;
  summary["odometry_rejected_motions"] = odometry_rejected_motions;
  summary["odometry_held_scans"] = odometry_held_scans;
  summary["threads"] = options.threads;
  summary["wall_time_s"] = wall_s;
  summary["frames_per_second"] = wall_s > 0 ? frames / wall_s : 0.0;
  summary["stage_clock"] = options.cpu_time ? "thread CPU" : "wall";
  summary["frame_ms"] = statistics(outputs.total_ms);
  for (const auto& [stage, values] : outputs.stage_ms)
    summary["stage_ms"][stage] = statistics(values);
  summary["peak_rss_mb"] = peak_resident_memory_mb();
  batch.add(outputs.path("summary.json"), [&](const std::string& path) {
    std::ofstream file(path);
    file << summary.dump(2) << "\n";
    if (!file) throw IoError(path + ": cannot write");
  });
  outputs.commit(!options.localize.empty());
  batch.commit();

  const nlohmann::json& frame_ms = summary["frame_ms"];
  std::printf(
      "frames %d, keyframes %zu, %.1f frames/s, frame ms mean %.1f p95 %.1f max %.1f, "
      "peak RSS %.0f MB\noutputs in %s\n",
      frames, pipeline->keyframes().size(), frames / std::max(wall_s, 1e-9),
      frame_ms.is_null() ? 0.0 : frame_ms["mean"].get<double>(),
      frame_ms.is_null() ? 0.0 : frame_ms["p95"].get<double>(),
      frame_ms.is_null() ? 0.0 : frame_ms["max"].get<double>(), peak_resident_memory_mb(),
      options.output.c_str());
  if (!options.localize.empty()) {
    std::printf("localization: %d of %d scans tracked, %d lost, %d alignments (%d accepted)\n",
                localization.tracked, frames, localization.lost, localization.alignments,
                localization.accepted);
  }
  return tools::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Run adaptive_lego_loam over a sequence: KITTI folder (velodyne/*.bin), a folder of "
      ".bin/.pcd scans, or a bag. Writes poses_kitti.txt, poses_tum.txt, timing.csv, "
      "degeneration.csv, loops.csv and summary.json to the output folder, each put in place only "
      "when the run succeeds."};
  Options options;
  app.add_option("--config", options.config,
                 "sensor config (config/*.yaml); more files (--config A --config B) replace "
                 "the keys of the earlier ones, e.g. a simulated drive's sensors.yaml")
      ->required();
  app.add_option("--input", options.input, "KITTI sequence folder, scan folder or .bag")
      ->required();
  app.add_option("--topic", options.topic, "PointCloud2 topic in a bag (default: its only one)");
  auto* beta0 = app.add_option("--beta0", options.beta0,
                               "fixed depth-clustering threshold (deg): "
                               "LeGO-LOAM mode")
                    ->check(CLI::Range(0.1, 89.9));
  auto* adaptive =
      app.add_flag("--adaptive", options.adaptive, "adaptive beta0 from the degeneration degree")
          ->excludes(beta0);
  app.add_flag("--no-segmentation", options.no_segmentation,
               "keep every non-ground point, however small its cluster (LOAM-like baseline)")
      ->excludes(beta0)
      ->excludes(adaptive);
  app.add_option("--max-frames", options.max_frames, "stop after this many frames")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--output", options.output, "output folder")->required();
  app.add_flag("--cpu-time", options.cpu_time,
               "stage times (timing.csv, summary.json) in thread CPU time instead of wall-clock "
               "time: what the stages cost on a machine shared with other work");
  app.add_option("--threads", options.threads,
                 "threads (1: the default): with 2 or more the next scan's ambient filter runs "
                 "while this one is registered, and the scan-to-map search is shared; the same "
                 "poses to the last bit")
      ->check(CLI::Range(1, 64));
  app.add_flag("--skip-bad-scans", options.skip_bad_scans,
               "go on past a scan that cannot be read (a warning; its pose is predicted and it is "
               "counted as skipped_scans in summary.json); default: stop there");
  auto* save_map_option =
      app.add_option("--save-map", options.save_map,
                     "save the map in this folder at the end (PCD maps, keyframes, poses; "
                     "written atomically)");
  auto* localize =
      app.add_option("--localize", options.localize,
                     "localize on the map saved in this folder instead of mapping (no new "
                     "keyframes join it, no loop closure); writes localization.csv")
          ->excludes(save_map_option);
  app.add_option("--initial-pose", options.initial_pose,
                 "with --localize: the first scan's pose in the map, X,Y,Z,YAW_DEG "
                 "(default 0,0,0,0: where the map's drive started)")
      ->delimiter(',')
      ->expected(4)
      ->needs(localize);
  auto* imu = app.add_option("--imu", options.imu,
                             "IMU samples (CSV: time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,"
                             "accel_z; docs/TOOLS.md): de-skewing, the guess, priors");
  app.add_option("--imu-topic", options.imu_topic,
                 "with a bag: its sensor_msgs/Imu topic instead of --imu")
      ->excludes(imu);
  auto* wheel = app.add_option("--wheel-odom", options.wheel_odom,
                               "wheel odometry (CSV: time,linear_x,...,angular_z_variance; "
                               "docs/TOOLS.md): the guess and a prior");
  app.add_option("--wheel-odom-topic", options.wheel_odom_topic,
                 "with a bag: its nav_msgs/Odometry topic instead of --wheel-odom")
      ->excludes(wheel);
  if (const auto status = tools::parse_command_line(app, argc, argv, "run_sequence")) {
    return *status;
  }
  if (options.cpu_time) set_stage_clock(Clock::kThreadCpu);
  return tools::run_job("run_sequence", [&] { return run(options); });
}
