// The clustering benchmark of the paper's Table I: runs one clustering method (or all six) over
// a folder of ground-free scans and prints the precision (mean best 3D IoU per labelled box) and
// the mean milliseconds per frame of the clustering, with the projection timed apart.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/eval/clustering_benchmark.h"
#include "adaptive_lego_loam/eval/clustering_methods.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/progress.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Frame {
  std::string name;  // file name without extension
  std::string points_path;
  std::optional<std::vector<LabelledObject>> objects;  // empty when the frame has no label file
};

// Per method, summed over frames.
struct MethodResult {
  ClusteringMethod method = ClusteringMethod::kAdaptive;
  PrecisionScore score;
  std::vector<double> object_iou;  // best IoU per labelled box, in frame order
  std::vector<std::optional<AxisAlignedBox>> object_match;  // the cluster box giving it
  int frames = 0;
  int cut = 0, merged = 0;  // boxes scoring under 0.5, by the cause below
  double preparation_ms = 0.0, clustering_ms = 0.0;
  long clusters = 0, unclustered_points = 0, dropped_by_projection = 0;
};

std::vector<Frame> load_frames(const std::string& points_dir, const std::string& labels_dir) {
  if (!fs::is_directory(labels_dir)) throw IoError(labels_dir + ": not a directory of labels");
  std::vector<Frame> frames;
  for (const std::string& path : list_scan_files(points_dir)) {
    Frame frame{fs::path(path).stem().string(), path, std::nullopt};
    const fs::path label_path = fs::path(labels_dir) / (frame.name + ".txt");
    if (fs::exists(label_path)) frame.objects = read_object_labels(label_path.string());
    frames.push_back(std::move(frame));
  }
  if (frames.empty()) throw IoError(points_dir + ": no .pcd or .bin scan in it");
  const bool any_labelled = std::any_of(
      frames.begin(), frames.end(), [](const Frame& frame) { return frame.objects.has_value(); });
  if (!any_labelled)
    throw IoError(labels_dir + ": no label file named like a scan of " + points_dir);
  return frames;
}

// The share of `cluster`'s volume inside `object`'s box (0 for an empty cluster box).
double share_inside(const AxisAlignedBox& cluster, const AxisAlignedBox& object) {
  double inside = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    inside *= std::max(0.0, std::min(cluster.max[axis], object.max[axis]) -
                                std::max(cluster.min[axis], object.min[axis]));
  }
  return cluster.volume() > 0.0 ? inside / cluster.volume() : 0.0;
}

// Why a box scored under 0.5: its best cluster lies mostly inside it (the object was cut into
// pieces) or reaches well beyond it (merged with its surroundings).
void count_cause(const AxisAlignedBox& object, const std::vector<AxisAlignedBox>& boxes,
                 const BestMatch& match, MethodResult& result) {
  if (match.iou >= 0.5 || match.cluster < 0) return;
  if (share_inside(boxes[match.cluster], object) >= 0.8) {
    ++result.cut;
  } else {
    ++result.merged;
  }
}

void run_frame(const Frame& frame, const Scan& scan, ClusteringRunner& runner,
               MethodResult& result) {
  ScanClustering clustering;
  runner.cluster(scan, clustering);
  ++result.frames;
  result.preparation_ms += clustering.preparation_ms;
  result.clustering_ms += clustering.clustering_ms;
  result.clusters += clustering.clusters;
  result.unclustered_points += clustering.unclustered_points;
  result.dropped_by_projection += clustering.dropped_by_projection;
  if (!frame.objects) return;
  const std::vector<AxisAlignedBox> boxes = cluster_boxes(scan.points, clustering.cluster_of_point);
  result.score.add_frame(*frame.objects, boxes);
  for (const LabelledObject& object : *frame.objects) {
    const BestMatch match = best_match(object.box, boxes);
    result.object_iou.push_back(match.iou);
    count_cause(object.box, boxes, match, result);
    result.object_match.push_back(match.cluster >= 0 ? std::optional(boxes[match.cluster])
                                                     : std::nullopt);
  }
}

std::vector<MethodResult> run_benchmark(const std::vector<Frame>& frames, const Config& config,
                                        const std::vector<ClusteringMethod>& methods) {
  std::vector<std::unique_ptr<ClusteringRunner>> runners;
  std::vector<MethodResult> results;
  for (ClusteringMethod method : methods) {
    runners.push_back(std::make_unique<ClusteringRunner>(method, config));
    results.emplace_back();
    results.back().method = method;
  }
  // One untimed pass over the first frame: the range-image methods reuse their buffers from
  // frame to frame, as in a running pipeline, and their first allocation is not clustering.
  ScanClustering warm_up;
  const Scan first = read_scan_file(frames.front().points_path);
  for (auto& runner : runners)
    runner->cluster(first, warm_up);
  ProgressBar progress("segmentation_bench", static_cast<int>(frames.size()));
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const Scan scan = read_scan_file(frames[f].points_path);
    // Every method clusters the frame before the next frame is read: they share its conditions.
    for (std::size_t m = 0; m < methods.size(); ++m)
      run_frame(frames[f], scan, *runners[m], results[m]);
    progress.update(static_cast<int>(f) + 1);
  }
  progress.finish();
  return results;
}

const char* preparation_name(ClusteringMethod method) {
  if (uses_range_image(method)) return "projection";
  return method == ClusteringMethod::kEuclideanKdtree ? "PCL cloud" : "none";
}

void print_header(const std::vector<Frame>& frames, const MethodResult& any, const Config& config) {
  std::printf(
      "%zu frames, %d with labels (%d labelled boxes; frames without labels are timed, not "
      "scored)\n",
      frames.size(), any.score.frames(), any.score.objects());
  std::printf(
      "config %s: window w %d, gamma %.3g, %s criterion; clusters of at least %d points counted\n",
      config.source.c_str(), config.ambient.euclidean_window, config.ambient.euclidean_gamma,
      to_string(config.ambient.euclidean_criterion),
      config.clustering_benchmark.min_cluster_points);
}

void print_table(const std::vector<MethodResult>& results) {
  std::printf("%-17s %11s %11s %9s  %-11s %15s %18s %13s\n", "method", "precision_%", "cluster_ms",
              "prep_ms", "prep", "clusters/frame", "unclustered/frame", "cut/merged*");
  for (const MethodResult& r : results) {
    const double frames = std::max(1, r.frames);
    std::printf("%-17s %11.1f %11.2f %9.2f  %-11s %15.0f %18.0f %13s\n",
                method_name(r.method).c_str(), 100.0 * r.score.precision(),
                r.clustering_ms / frames, r.preparation_ms / frames, preparation_name(r.method),
                r.clusters / frames, r.unclustered_points / frames,
                (std::to_string(r.cut) + "/" + std::to_string(r.merged)).c_str());
  }
  std::printf(
      "* labelled boxes scoring under 0.5 whose best cluster lies mostly (80 %%) inside "
      "the box / reaches beyond it\n");
}

const MethodResult* find_result(const std::vector<MethodResult>& results, ClusteringMethod method) {
  for (const MethodResult& r : results)
    if (r.method == method) return &r;
  return nullptr;
}

// The paper's claim for Table I, when both methods ran: the adaptive clustering's precision
// against the KD-tree's, and how much faster it is.
void print_comparison(const std::vector<MethodResult>& results) {
  const MethodResult* adaptive = find_result(results, ClusteringMethod::kAdaptive);
  const MethodResult* kdtree = find_result(results, ClusteringMethod::kEuclideanKdtree);
  if (!adaptive || !kdtree || kdtree->score.precision() <= 0.0) return;
  std::printf(
      "adaptive / euclidean_kdtree: precision x%.2f; %.0f times faster (clustering), %.0f times "
      "with its projection\n",
      adaptive->score.precision() / kdtree->score.precision(),
      kdtree->clustering_ms / adaptive->clustering_ms,
      kdtree->clustering_ms / (adaptive->clustering_ms + adaptive->preparation_ms));
}

json to_json(const std::vector<Frame>& frames, const std::vector<MethodResult>& results,
             const Config& config) {
  json objects = json::array();
  for (const Frame& frame : frames) {
    if (!frame.objects) continue;
    for (const LabelledObject& object : *frame.objects) {
      objects.push_back({{"frame", frame.name},
                         {"class", object.object_class},
                         {"min", object.box.min},
                         {"max", object.box.max}});
    }
  }
  json methods = json::array();
  for (const MethodResult& r : results) {
    json matches = json::array();
    for (const auto& box : r.object_match) {
      matches.push_back(box ? json{{"min", box->min}, {"max", box->max}} : json(nullptr));
    }
    const double n = std::max(1, r.frames);
    methods.push_back({{"method", method_name(r.method)},
                       {"precision_percent", 100.0 * r.score.precision()},
                       {"clustering_ms_per_frame", r.clustering_ms / n},
                       {"preparation_ms_per_frame", r.preparation_ms / n},
                       {"preparation", preparation_name(r.method)},
                       {"clusters_per_frame", r.clusters / n},
                       {"unclustered_points_per_frame", r.unclustered_points / n},
                       {"boxes_under_half_cut", r.cut},
                       {"boxes_under_half_merged", r.merged},
                       {"dropped_by_projection_per_frame", r.dropped_by_projection / n},
                       {"object_iou", r.object_iou},
                       {"object_best_cluster", matches}});
  }
  return {{"config", config.source},
          {"euclidean_window", config.ambient.euclidean_window},
          {"euclidean_gamma", config.ambient.euclidean_gamma},
          {"euclidean_criterion", to_string(config.ambient.euclidean_criterion)},
          {"min_cluster_points", config.clustering_benchmark.min_cluster_points},
          {"frames", frames.size()},
          {"labelled_frames", results.front().score.frames()},
          {"objects", objects},
          {"methods", methods}};
}

void write_json(const std::string& path, const json& document) {
  std::ofstream file(path, std::ios::trunc);
  if (!file) throw IoError(path + ": cannot open for writing");
  file << document.dump(2) << '\n';
  file.close();
  if (!file) throw IoError(path + ": write failed");
}

std::vector<ClusteringMethod> methods_from_name(const std::string& name) {
  if (name == "all") return all_clustering_methods();
  const std::optional<ClusteringMethod> method = method_from_name(name);
  if (!method) {
    std::string known;
    for (ClusteringMethod m : all_clustering_methods())
      known += method_name(m) + ", ";
    throw std::invalid_argument("unknown method '" + name + "'; expected one of " + known + "all");
  }
  return {*method};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Clustering benchmark of the paper's Table I on ground-free scans with object boxes: "
      "precision = mean over labelled boxes of the best 3D IoU of any cluster's box (0 if none), "
      "and mean ms per frame of the clustering (projection apart)."};
  std::string points_dir, labels_dir, method_arg, json_path;
  std::string config_path = std::string(CONFIG_DIR) + "/kitti.yaml";
  std::optional<int> window;
  std::optional<double> gamma;
  std::optional<std::string> criterion;
  app.add_option("--points", points_dir, "folder of ground-free scans (.pcd or .bin)")->required();
  app.add_option("--labels", labels_dir, "folder of label files (same base name, .txt)")
      ->required();
  app.add_option("--method", method_arg,
                 "adaptive, ccl_euclidean, depth, run, euclidean_kdtree, dbscan, or all")
      ->required();
  app.add_option("--config", config_path, "sensor config")->capture_default_str();
  app.add_option("--window", window,
                 "override ambient_filter.euclidean_window (w, also ccl_euclidean's)")
      ->check(CLI::Range(1, 10));
  app.add_option("--gamma", gamma, "override ambient_filter.euclidean_gamma")
      ->check(CLI::Range(0.1, 100.0));
  app.add_option("--criterion", criterion,
                 "override ambient_filter.euclidean_criterion: distance (the paper's text) or "
                 "range_difference (the authors' code)")
      ->check(CLI::IsMember({"distance", "range_difference"}));
  app.add_option("--json", json_path, "also write the results, with each box's IoU, to this file");
  if (const auto status = tools::parse_command_line(app, argc, argv, "segmentation_bench")) {
    return *status;
  }
  return tools::run_job("segmentation_bench", [&] {
    const std::vector<ClusteringMethod> methods = methods_from_name(method_arg);
    Config config = load_config(config_path);
    if (window) config.ambient.euclidean_window = *window;
    if (gamma) config.ambient.euclidean_gamma = *gamma;
    if (criterion) {
      config.ambient.euclidean_criterion = *criterion == "distance"
                                               ? EuclideanCriterion::kDistance
                                               : EuclideanCriterion::kRangeDifference;
    }
    const std::vector<Frame> frames = load_frames(points_dir, labels_dir);
    const std::vector<MethodResult> results = run_benchmark(frames, config, methods);
    print_header(frames, results.front(), config);
    print_table(results);
    print_comparison(results);
    if (!json_path.empty()) write_json(json_path, to_json(frames, results, config));
    return tools::kExitOk;
  });
}
