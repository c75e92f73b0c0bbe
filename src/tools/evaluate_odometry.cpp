// Compares an estimated trajectory with ground truth (both KITTI pose files) and prints the KITTI
// segment errors, the RPE, the ATE and the drift at the end of docs/METHOD.md, optionally beside a
// dead-reckoning baseline's drift; with a simulated sequence's observability.csv and the run's
// degeneration.csv, how well its degenerate flag and covariance match the truth; --json writes
// the same numbers.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "adaptive_lego_loam/eval/degeneration_evaluation.h"
#include "adaptive_lego_loam/eval/metrics.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/motion_sensor_files.h"
#include "adaptive_lego_loam/io/pose_files.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;
using nlohmann::json;

namespace {

json optional_number(const std::optional<double>& value) {
  return value ? json(*value) : json(nullptr);
}

// What --baseline asked for: a dead-reckoning trajectory whose drift is printed beside the
// estimate's.
struct Baseline {
  std::string name;
  std::vector<Eigen::Isometry3d> poses;
  EndDrift drift;
};

// The baselines --baseline knows; an unknown one is a usage error naming those it knows.
constexpr const char* kConstantVelocity = "constant-velocity";
constexpr const char* kWheel = "wheel";

std::optional<std::string> check_baseline(const std::vector<std::string>& arguments,
                                          bool has_times) {
  if (arguments.empty()) return std::nullopt;
  if (arguments[0] == kConstantVelocity) {
    if (arguments.size() > 1)
      return std::string("--baseline ") + kConstantVelocity + " takes no file";
    return std::nullopt;
  }
  if (arguments[0] == kWheel) {
    if (arguments.size() != 2) return "--baseline wheel needs the wheel odometry's CSV file";
    if (!has_times) return "--baseline wheel needs --times (the scans' stamps)";
    return std::nullopt;
  }
  return "--baseline: unknown baseline '" + arguments[0] + "' (expected " + kConstantVelocity +
         " or " + kWheel + " FILE)";
}

json drift_json(const EndDrift& drift) {
  return {{"reach_ratio", optional_number(drift.reach_ratio)},
          {"along_track_percent", optional_number(drift.along_track_percent)},
          {"cross_track_percent", optional_number(drift.cross_track_percent)},
          {"estimated_path_m", drift.estimated_path_m},
          {"ground_truth_path_m", drift.ground_truth_path_m}};
}

json to_json(const OdometryEvaluation& evaluation) {
  json per_length = json::array();
  for (const SegmentLengthError& length : evaluation.kitti.per_length) {
    per_length.push_back({{"length_m", length.length_m},
                          {"segments", length.segments},
                          {"t_err_percent", length.translation_percent},
                          {"r_err_deg_per_100m", length.rotation_deg_per_100m}});
  }
  json alignment = json::array();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col)
      alignment.push_back(evaluation.ate.alignment.matrix()(row, col));
  }
  return {{"frames",
           {{"estimate", evaluation.estimate_frames},
            {"ground_truth", evaluation.ground_truth_frames},
            {"used", evaluation.frames_used}}},
          {"kitti",
           {{"t_err_percent", optional_number(evaluation.kitti.translation_percent)},
            {"r_err_deg_per_100m", optional_number(evaluation.kitti.rotation_deg_per_100m)},
            {"segments", evaluation.kitti.segments},
            {"ground_truth_path_m", evaluation.kitti.ground_truth_path_m},
            {"per_length", per_length}}},
          {"rpe",
           {{"translation_rmse_m", optional_number(evaluation.rpe.translation_rmse_m)},
            {"rotation_rmse_deg", optional_number(evaluation.rpe.rotation_rmse_deg)},
            {"pairs", evaluation.rpe.translation_m.size()}}},
          {"ate", {{"rmse_m", evaluation.ate.rmse_m}, {"alignment_3x4_row_major", alignment}}},
          {"drift", drift_json(evaluation.drift)}};
}

void print_kitti(const KittiSegmentError& kitti) {
  std::printf("ground-truth path  %.3f m\n", kitti.ground_truth_path_m);
  if (kitti.segments == 0) {
    const std::vector<double> lengths = KittiSegmentOptions{}.lengths_m;
    std::printf("KITTI t_err        n/a (no segment: the path is shorter than %.0f m)\n",
                *std::min_element(lengths.begin(), lengths.end()));
    std::printf("KITTI r_err        n/a\n");
    return;
  }
  std::printf("KITTI t_err        %.4f %% (%d segments)\n", *kitti.translation_percent,
              kitti.segments);
  std::printf("KITTI r_err        %.4f deg/100 m\n", *kitti.rotation_deg_per_100m);
  std::printf("  %8s %8s %10s %16s\n", "length_m", "segments", "t_err_%", "r_err_deg/100m");
  for (const SegmentLengthError& length : kitti.per_length) {
    std::printf("  %8.0f %8d %10.4f %16.4f\n", length.length_m, length.segments,
                length.translation_percent, length.rotation_deg_per_100m);
  }
}

void print(const OdometryEvaluation& evaluation) {
  std::printf("frames used        %zu (estimate %zu, ground truth %zu)\n", evaluation.frames_used,
              evaluation.estimate_frames, evaluation.ground_truth_frames);
  print_kitti(evaluation.kitti);
  if (evaluation.rpe.translation_rmse_m) {
    std::printf("RPE RMSE           %.6f m per frame (rotation %.6f deg)\n",
                *evaluation.rpe.translation_rmse_m, *evaluation.rpe.rotation_rmse_deg);
  } else {
    std::printf("RPE RMSE           n/a (one frame)\n");
  }
  std::printf("ATE RMSE           %.6f m\n", evaluation.ate.rmse_m);
}

std::string cell(const std::optional<double>& value, const char* format) {
  if (!value) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), format, *value);
  return text;
}

// The drift at the end, the baseline's beside the estimate's.
void print_drift(const EndDrift& drift, const std::optional<Baseline>& baseline) {
  std::printf("drift at the end    %12s %18s\n", "estimate",
              baseline ? baseline->name.c_str() : "");
  auto row = [&](const char* label, auto field, const char* format) {
    std::printf("  %-17s %12s %18s\n", label, cell(field(drift), format).c_str(),
                baseline ? cell(field(baseline->drift), format).c_str() : "");
  };
  row(
      "reach ratio", [](const EndDrift& d) { return d.reach_ratio; }, "%.4f");
  row(
      "along-track %", [](const EndDrift& d) { return d.along_track_percent; }, "%+.3f");
  row(
      "cross-track %", [](const EndDrift& d) { return d.cross_track_percent; }, "%.3f");
}

json to_json(const DegenerationEvaluation& evaluation) {
  const DetectionScore& detection = evaluation.detection;
  const NeesSummary& nees = evaluation.nees;
  return {{"degenerate_translation_sigma_m", evaluation.degenerate_sigma_m},
          {"scans", evaluation.scans_compared},
          {"flag_source", to_string(evaluation.flag_source)},
          {"truly_degenerate", evaluation.truly_degenerate},
          {"flagged", evaluation.flagged},
          {"precision", optional_number(detection.precision)},
          {"recall", optional_number(detection.recall)},
          {"true_positives", detection.true_positives},
          {"false_positives", detection.false_positives},
          {"false_negatives", detection.false_negatives},
          {"true_negatives", detection.true_negatives},
          {"nees",
           {{"uncertainty_source", to_string(evaluation.uncertainty_source)},
            {"dof", nees.dof},
            {"bounds_95", {nees.bounds.lower, nees.bounds.upper}},
            {"scans", nees.scans},
            {"below", nees.below},
            {"within", nees.within},
            {"above", nees.above},
            {"share_within", optional_number(nees.share_within)},
            {"median", optional_number(nees.median_nees)},
            {"variance_scale", optional_number(nees.variance_scale)}}}};
}

std::string share(int count, int total) {
  return total > 0 ? cell(100.0 * count / total, "%.1f %%") : "n/a";
}

void print(const DegenerationEvaluation& evaluation) {
  const DetectionScore& detection = evaluation.detection;
  std::printf(
      "degenerate flag    precision %s recall %s (%d scans: %d truly degenerate, %d "
      "flagged; TP %d FP %d FN %d TN %d; flag: %s)\n",
      cell(detection.precision, "%.3f").c_str(), cell(detection.recall, "%.3f").c_str(),
      evaluation.scans_compared, evaluation.truly_degenerate, evaluation.flagged,
      detection.true_positives, detection.false_positives, detection.false_negatives,
      detection.true_negatives, to_string(evaluation.flag_source));
  const NeesSummary& nees = evaluation.nees;
  std::printf(
      "covariance NEES    %s of %d scans within [%.3g, %.3g] (%d DOF, 95 %%), %s above, "
      "%s below; median %s, %s x chi-square's (%s)\n",
      share(nees.within, nees.scans).c_str(), nees.scans, nees.bounds.lower, nees.bounds.upper,
      nees.dof, share(nees.above, nees.scans).c_str(), share(nees.below, nees.scans).c_str(),
      cell(nees.median_nees, "%.3g").c_str(), cell(nees.variance_scale, "%.3g").c_str(),
      to_string(evaluation.uncertainty_source));
}

void write_json(const std::string& path, const json& document) {
  std::ofstream file(path, std::ios::trunc);
  if (!file) throw IoError(path + ": cannot open for writing");
  file << document.dump(2) << '\n';
  file.close();
  if (!file) throw IoError(path + ": write failed");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Compare an estimated trajectory with ground truth (KITTI pose files, index i = scan i): "
      "KITTI segment errors t_err (%) and r_err (deg/100 m), RPE RMSE (m per frame) and ATE "
      "RMSE (m, after a rigid alignment). A shorter estimate (interrupted run) is compared over "
      "its frames."};
  std::string gt_path, estimate_path, calib_path, json_path, times_path;
  std::string observability_path, degeneration_path;
  std::vector<std::string> baseline_arguments, config_paths;
  app.add_option("--gt", gt_path, "ground-truth poses (KITTI format)")->required();
  app.add_option("--est", estimate_path, "estimated poses (KITTI format, lidar frame)")->required();
  app.add_option("--calib", calib_path,
                 "KITTI calib.txt: its Tr converts camera ground truth to the lidar frame");
  app.add_option("--json", json_path, "also write the numbers to this JSON file");
  app.add_option(
         "--baseline", baseline_arguments,
         "also the drift of a dead-reckoning baseline: constant-velocity (the ground "
         "truth's mean velocity over its first second, in the sensor frame, kept for the "
         "whole drive), or wheel FILE (the wheel odometry's CSV, run_sequence --wheel-odom's "
         "format, integrated from the first true pose between the scans' --times)")
      ->expected(1, 2);
  app.add_option("--times", times_path,
                 "scan times (KITTI times.txt): the constant-velocity baseline's first second "
                 "(default: 10 scans a second), the wheel baseline's intervals");
  app.add_option("--config", config_paths,
                 "configs whose wheel_odometry section (extrinsic, time offset, max_gap_s) the "
                 "wheel baseline uses, later ones overriding (as run_sequence --config)")
      ->expected(1, -1);
  app.add_option("--observability", observability_path,
                 "a simulated sequence's observability.csv (the true information per scan): "
                 "scores the run's degenerate flag and covariance, with --degeneration");
  app.add_option("--degeneration", degeneration_path,
                 "the run's degeneration.csv (run_sequence): its degenerate flag, scored by "
                 "precision and recall against the truth, and its published covariance, by the "
                 "share of scans whose NEES is within the chi-square's 95 % bounds; --config's "
                 "mapping.degenerate_translation_sigma is the threshold");
  if (const auto status = tools::parse_command_line(app, argc, argv, "evaluate_odometry")) {
    return *status;
  }
  if (const auto error = check_baseline(baseline_arguments, !times_path.empty())) {
    return tools::usage_error("evaluate_odometry", *error);
  }
  if (!times_path.empty() && baseline_arguments.empty()) {
    return tools::usage_error("evaluate_odometry", "--times applies to --baseline only");
  }
  if (observability_path.empty() != degeneration_path.empty()) {
    return tools::usage_error("evaluate_odometry",
                              "--observability and --degeneration go together");
  }
  const bool wheel_baseline_asked = !baseline_arguments.empty() && baseline_arguments[0] == kWheel;
  if (!config_paths.empty() && !wheel_baseline_asked && observability_path.empty()) {
    return tools::usage_error("evaluate_odometry",
                              "--config applies to --baseline wheel and --observability only");
  }
  return tools::run_job("evaluate_odometry", [&] {
    std::vector<Eigen::Isometry3d> ground_truth = read_kitti_poses(gt_path);
    const std::vector<Eigen::Isometry3d> estimate = read_kitti_poses(estimate_path);
    if (!calib_path.empty()) {
      ground_truth = camera_to_lidar_poses(ground_truth, read_kitti_calib_tr(calib_path));
    }
    const OdometryEvaluation evaluation = evaluate_odometry(estimate, ground_truth);
    if (estimate.size() != ground_truth.size()) {
      std::fprintf(stderr,
                   "evaluate_odometry: warning: estimate has %zu poses, ground truth %zu; "
                   "comparing the first %zu\n",
                   estimate.size(), ground_truth.size(), evaluation.frames_used);
    }
    std::optional<Baseline> baseline;
    std::size_t window = 10;  // 10 scans a second
    if (!baseline_arguments.empty()) {
      const std::vector<double> times =
          times_path.empty() ? std::vector<double>{} : read_kitti_times(times_path);
      const std::vector<Eigen::Isometry3d> truth_used(
          ground_truth.begin(),
          ground_truth.begin() + static_cast<std::ptrdiff_t>(evaluation.frames_used));
      baseline = Baseline{baseline_arguments[0], {}, {}};
      if (baseline_arguments[0] == kWheel) {
        const WheelOdometryParams params =
            config_paths.empty() ? WheelOdometryParams{} : load_config(config_paths).wheel_odometry;
        if (times.size() < truth_used.size()) {
          throw IoError(times_path + ": " + std::to_string(times.size()) +
                        " scan times, expected one for each of the " +
                        std::to_string(truth_used.size()) + " poses");
        }
        baseline->poses = wheel_baseline(truth_used, times,
                                         read_wheel_odometry_csv(baseline_arguments[1]), params);
      } else {
        if (!times.empty()) window = steps_within(times, 1.0);
        baseline->poses = constant_velocity_baseline(truth_used, window);
      }
      baseline->drift = end_drift(baseline->poses, truth_used);
    }
    std::optional<DegenerationEvaluation> degeneration;
    if (!observability_path.empty()) {
      const double degenerate_sigma_m =
          config_paths.empty() ? MappingParams{}.degenerate_translation_sigma
                               : load_config(config_paths).mapping.degenerate_translation_sigma;
      // The truth first: its errors before the run's.
      const std::vector<TrueObservability> truth = read_observability_csv(observability_path);
      const RunDegeneration run = read_degeneration_csv(degeneration_path, degenerate_sigma_m);
      degeneration = evaluate_degeneration(truth, run, estimate, ground_truth, degenerate_sigma_m);
    }
    if (!json_path.empty()) {
      json document = to_json(evaluation);
      if (degeneration) document["degeneration"] = to_json(*degeneration);
      if (baseline) {
        document["baseline"] = {{"name", baseline->name}, {"drift", drift_json(baseline->drift)}};
        if (baseline->name == kConstantVelocity)
          document["baseline"]["first_second_steps"] = window;
      }
      write_json(json_path, document);
    }
    print(evaluation);
    print_drift(evaluation.drift, baseline);
    if (degeneration) print(*degeneration);
    return tools::kExitOk;
  });
}
