// Runs the whole pipeline over a sequence (KITTI folder, PCD folder or bag) and writes the poses
// (KITTI and TUM), per-frame stage times, the ambient filter's output and a summary.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "adaptive_lego_loam/io/progress.h"
#include "adaptive_lego_loam/io/scan_sequence.h"
#include "adaptive_lego_loam/ros/bag_sequence.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;
namespace fs = std::filesystem;

namespace {

// The columns of timing.csv, in pipeline order; stages a frame did not run are 0.
const std::vector<std::string> kStages = {
    "projection",       "ground",          "euclidean_clustering",
    "skeleton",         "normals",         "degeneration",
    "depth_clustering", "segmented_cloud", "deskew",
    "features",         "odometry",        "local_map",
    "mapping",          "keyframes",       "loop_closure"};

struct Options {
  std::string config, input, topic, output;
  double beta0 = -1.0;
  bool adaptive = false;
  int max_frames = -1;
  bool cpu_time = false;
};

std::unique_ptr<ScanSequence> open_sequence(const Options& options) {
  if (fs::is_directory(options.input)) return open_folder_sequence(options.input);
  if (fs::path(options.input).extension() == ".bag") {
    return ros_bridge::open_bag_sequence(options.input, options.topic);
  }
  throw IoError(options.input +
                ": expected a KITTI sequence folder, a folder of .bin/.pcd scans "
                "or a .bag file");
}

class Outputs {
 public:
  explicit Outputs(const std::string& dir) : dir_(dir) {
    fs::create_directories(dir);
    timing_.open(path("timing.csv"));
    degeneration_.open(path("degeneration.csv"));
    loops_.open(path("loops.csv"));
    if (!timing_ || !degeneration_ || !loops_) throw IoError(dir + ": cannot write outputs there");
    loops_ << "frame,current_keyframe,matched_keyframe,current_frame,matched_frame,source,status,"
              "inlier_ratio,inlier_mse,fitness,relative_x,relative_y,relative_z,relative_yaw_deg,"
              "closed\n";
    timing_ << "frame";
    for (const auto& stage : kStages)
      timing_ << "," << stage;
    timing_ << ",total,rss_mb\n";
    degeneration_ << "frame,mu,beta0_deg,direction_x,direction_y,skeleton_points,normals,valid,"
                     "map_degenerate_directions\n";
  }

  std::string path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

  // A loop-closure attempt that finished on a scan, or loops that entered the graph on it.
  void add_loop(int frame, const std::optional<LoopDetection>& loop, bool closed,
                const std::vector<Keyframe>& keyframes) {
    if (!loop && !closed) return;
    loops_ << frame << ",";
    if (loop) {
      const auto frame_of = [&](int keyframe) {
        return keyframe >= 0 ? std::to_string(keyframes.at(keyframe).frame) : std::string();
      };
      const Eigen::Isometry3d& relative = loop->relative_pose;
      loops_ << loop->current_index << "," << loop->matched_index << ","
             << frame_of(loop->current_index) << "," << frame_of(loop->matched_index) << ","
             << (loop->source == CandidateSource::kPlace ? "place" : "radius") << ","
             << (loop->accepted() ? "verified" : to_string(loop->status)) << ","
             << loop->inlier_ratio << "," << loop->inlier_mse << "," << loop->fitness << ","
             << relative.translation().x() << "," << relative.translation().y() << ","
             << relative.translation().z() << ","
             << std::atan2(relative(1, 0), relative(0, 0)) * 180.0 / M_PI;
    } else {
      loops_ << ",,,,,,,,,,,,,";
    }
    loops_ << "," << int(closed) << "\n";
  }

  void add(const FrameResult& frame, const AmbientFilterResult& filtered) {
    timing_ << frame.frame;
    for (const auto& stage : kStages)
      timing_ << "," << frame.times.get(stage);
    timing_ << "," << frame.times.total() << "," << resident_memory_mb() << "\n";
    const Degeneration& d = filtered.degeneration;
    degeneration_ << frame.frame << "," << filtered.mu << "," << filtered.beta0_deg << ","
                  << d.weak_direction.x() << "," << d.weak_direction.y() << ","
                  << filtered.skeleton_points << "," << d.normals << "," << int(d.valid) << ","
                  << frame.mapping.degenerate_directions << "\n";
    stamps.push_back(frame.stamp);
    for (const auto& [stage, ms] : frame.times.entries())
      stage_ms[stage].push_back(ms);
    total_ms.push_back(frame.times.total());
  }

  std::vector<double> stamps;
  std::map<std::string, std::vector<double>> stage_ms;
  std::vector<double> total_ms;

 private:
  std::string dir_;
  std::ofstream timing_, degeneration_, loops_;
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

void write_poses(const Options& options, const Pipeline& pipeline, const Outputs& outputs) {
  const std::vector<Eigen::Isometry3d> poses = pipeline.trajectory();
  write_kitti_poses(outputs.path("poses_kitti.txt"), poses);
  write_tum_poses(outputs.path("poses_tum.txt"), outputs.stamps, poses);
  // KITTI's ground truth is in the left camera's frame: with a calib.txt beside the scans, also
  // write the poses there (camera pose = Tr * lidar pose * Tr^-1).
  if (const auto calib = kitti_calib_beside(options.input)) {
    const Eigen::Isometry3d tr = read_kitti_calib_tr(*calib);
    std::vector<Eigen::Isometry3d> camera;
    for (const auto& pose : poses)
      camera.push_back(tr * pose * tr.inverse());
    write_kitti_poses(outputs.path("poses_camera.txt"), camera);
  }
}

int run(const Options& options) {
  Config config = load_config(options.config);
  if (options.beta0 > 0.0) {
    config.ambient.mode = Beta0Mode::kFixed;
    config.ambient.fixed_beta0_deg = options.beta0;
  } else if (options.adaptive) {
    config.ambient.mode = Beta0Mode::kAdaptive;
  }
  std::unique_ptr<ScanSequence> sequence = open_sequence(options);
  Outputs outputs(options.output);
  Pipeline pipeline(config);
  const int total = options.max_frames >= 0 && sequence->size() >= 0
                        ? std::min(options.max_frames, sequence->size())
                        : sequence->size();
  std::fprintf(stderr, "run_sequence: %s, config %s, %s\n", sequence->describe().c_str(),
               options.config.c_str(),
               config.ambient.mode == Beta0Mode::kAdaptive
                   ? "adaptive beta0"
                   : ("fixed beta0 " + std::to_string(config.ambient.fixed_beta0_deg)).c_str());
  ProgressBar progress("run_sequence", total);
  Stopwatch wall(Clock::kWall);
  int frames = 0, empty_scans = 0, motion_gated_scans = 0;
  std::string failure;
  try {
    while (options.max_frames < 0 || frames < options.max_frames) {
      std::optional<Scan> scan = sequence->next();
      if (!scan) break;
      const FrameResult& result = pipeline.process(*scan);
      empty_scans += !result.valid_scan;
      motion_gated_scans += result.motion_gated;
      outputs.add(result, pipeline.filter_result());
      outputs.add_loop(result.frame, result.loop, result.loop_closed, pipeline.keyframes());
      progress.update(++frames);
    }
  } catch (const std::exception& e) {
    failure = e.what();  // keep what was done so far
  }
  progress.finish();
  // A loop closure still running at the end of the input finishes now, outside every scan's
  // time: the online mapping would finish it over the next scans.
  nlohmann::json final_loop_closure;
  if (failure.empty()) {
    const Stopwatch stopwatch;
    if (const std::optional<LoopDetection> loop = pipeline.finish_loop_closure()) {
      final_loop_closure = {{"status", to_string(loop->status)},
                            {"fitness", loop->fitness},
                            {"ms", stopwatch.elapsed_ms()}};
    }
  }
  const double wall_s = wall.elapsed_ms() / 1000.0;
  if (frames > 0) write_poses(options, pipeline, outputs);

  nlohmann::json summary;
  summary["input"] = options.input;
  summary["config"] = options.config;
  summary["beta0_mode"] = config.ambient.mode == Beta0Mode::kAdaptive ? "adaptive" : "fixed";
  if (config.ambient.mode == Beta0Mode::kFixed)
    summary["beta0_deg"] = config.ambient.fixed_beta0_deg;
  summary["frames"] = frames;
  summary["scans_without_valid_points"] = empty_scans;
  summary["keyframes"] = pipeline.keyframes().size();
  summary["loops_closed"] = pipeline.mapping().loops_closed();
  const LoopClosureCounts& loops = pipeline.mapping().loop_closure_counts();
  summary["loop_closure"] = {{"place_candidates", loops.place_candidates},
                             {"radius_candidates", loops.radius_candidates},
                             {"verified", loops.verified},
                             {"rejected", loops.rejected},
                             {"unconfirmed", loops.unconfirmed},
                             {"closed", loops.closed},
                             {"removed", loops.removed}};
  if (!final_loop_closure.is_null()) summary["loop_closure_after_last_scan"] = final_loop_closure;
  summary["motion_gated_scans"] = motion_gated_scans;
  summary["wall_time_s"] = wall_s;
  summary["frames_per_second"] = wall_s > 0 ? frames / wall_s : 0.0;
  summary["stage_clock"] = options.cpu_time ? "thread CPU" : "wall";
  summary["frame_ms"] = statistics(outputs.total_ms);
  for (const auto& [stage, values] : outputs.stage_ms)
    summary["stage_ms"][stage] = statistics(values);
  summary["peak_rss_mb"] = peak_resident_memory_mb();
  if (!failure.empty()) summary["error"] = failure;
  std::ofstream(outputs.path("summary.json")) << summary.dump(2) << "\n";

  if (!failure.empty()) {
    std::fprintf(stderr, "run_sequence: %s (after %d frames; their outputs are written)\n",
                 failure.c_str(), frames);
    return tools::kExitFailure;
  }
  const nlohmann::json& frame_ms = summary["frame_ms"];
  std::printf(
      "frames %d, keyframes %zu, %.1f frames/s, frame ms mean %.1f p95 %.1f max %.1f, "
      "peak RSS %.0f MB\noutputs in %s\n",
      frames, pipeline.keyframes().size(), frames / std::max(wall_s, 1e-9),
      frame_ms.is_null() ? 0.0 : frame_ms["mean"].get<double>(),
      frame_ms.is_null() ? 0.0 : frame_ms["p95"].get<double>(),
      frame_ms.is_null() ? 0.0 : frame_ms["max"].get<double>(), peak_resident_memory_mb(),
      options.output.c_str());
  return tools::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Run adaptive_lego_loam over a sequence: KITTI folder (velodyne/*.bin), a folder of "
      ".bin/.pcd scans, or a bag. Writes poses_kitti.txt, poses_tum.txt, timing.csv, "
      "degeneration.csv and summary.json to the output folder."};
  Options options;
  app.add_option("--config", options.config, "sensor config (config/*.yaml)")->required();
  app.add_option("--input", options.input, "KITTI sequence folder, scan folder or .bag")
      ->required();
  app.add_option("--topic", options.topic, "PointCloud2 topic in a bag (default: its only one)");
  auto* beta0 = app.add_option("--beta0", options.beta0,
                               "fixed depth-clustering threshold (deg): "
                               "LeGO-LOAM mode")
                    ->check(CLI::Range(0.1, 89.9));
  app.add_flag("--adaptive", options.adaptive, "adaptive beta0 from the degeneration degree")
      ->excludes(beta0);
  app.add_option("--max-frames", options.max_frames, "stop after this many frames")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--output", options.output, "output folder")->required();
  app.add_flag("--cpu-time", options.cpu_time,
               "stage times (timing.csv, summary.json) in thread CPU time instead of wall-clock "
               "time: what the stages cost on a machine shared with other work");
  if (const auto status = tools::parse_command_line(app, argc, argv, "run_sequence")) {
    return *status;
  }
  if (options.cpu_time) set_stage_clock(Clock::kThreadCpu);
  return tools::run_job("run_sequence", [&] { return run(options); });
}
