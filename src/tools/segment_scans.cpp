// Segments scans as LeGO-LOAM's imageProjection does (projection, ground, depth clustering with
// one beta0) and prints per frame what was kept and how long each stage took; or, with
// --degeneration, the degeneration degree mu as the ambient filter finds it on the range image and
// as a KD-tree over every non-ground point finds it (the paper's Fig. 8), with their times.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;

namespace {

std::vector<std::string> scan_files(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const std::string& input : inputs) {
    if (std::filesystem::is_directory(input)) {
      for (const std::string& file : list_scan_files(input))
        files.push_back(file);
    } else {
      files.push_back(input);
    }
  }
  return files;
}

// mu from the skeleton's range-image normals (the filter's steps 4-7) and from a KD-tree radius
// search over every non-ground point, per scan, with the milliseconds each took.
void print_degeneration(Config config, const std::vector<std::string>& files) {
  config.ambient.mode = Beta0Mode::kAdaptive;
  AmbientFilter filter(config);
  AmbientFilterResult result;
  const KdTreeNormalParams kdtree = kdtree_normal_params(config);
  std::vector<NormalFeature> normals;
  std::printf("%-24s %8s %9s %8s %9s %9s %8s %9s\n", "frame", "mu", "beta0_deg", "normals",
              "image_ms", "mu_kdtree", "normals", "kdtree_ms");
  for (const std::string& file : files) {
    const Scan scan = read_scan_file(file);
    filter.process(scan, result);
    const StageTimes& t = result.times();
    const double image_ms = t.get("euclidean_clustering") + t.get("skeleton") + t.get("normals") +
                            t.get("degeneration");
    const Stopwatch watch;
    kdtree_normals(non_ground_points(result.segmentation), kdtree, normals);
    const Degeneration by_kdtree = degeneration_from_normals(normals);
    const double kdtree_ms = watch.elapsed_ms();
    std::printf("%-24s %8.4f %9.2f %8zu %9.2f %9.4f %8zu %9.2f\n",
                std::filesystem::path(file).filename().string().c_str(),
                result.degeneration.valid ? result.degeneration.mu : std::nan(""), result.beta0_deg,
                result.normals.size(), image_ms, by_kdtree.valid ? by_kdtree.mu : std::nan(""),
                normals.size(), kdtree_ms);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Segment LiDAR scans (range image, ground, depth clustering) and print per frame "
      "the points in, ground, kept points, clusters and ms per stage."};
  std::string config_path;
  std::vector<std::string> inputs;
  double beta0_deg = -1.0;
  app.add_option("--config", config_path, "sensor config (config/*.yaml)")->required();
  app.add_option("--beta0", beta0_deg, "depth-clustering threshold in degrees (default: config)")
      ->check(CLI::Range(0.1, 89.9));
  bool degeneration = false;
  app.add_flag("--degeneration", degeneration,
               "print mu from the range image (the ambient filter) and from a KD-tree over every "
               "non-ground point, with their times, instead of the segmentation");
  app.add_option("inputs", inputs, "scan files (.bin, .pcd) or folders of them")->required();
  if (const auto status = tools::parse_command_line(app, argc, argv, "segment_scans")) {
    return *status;
  }
  return tools::run_job("segment_scans", [&] {
    const Config config = load_config(config_path);
    if (beta0_deg < 0) beta0_deg = config.segmentation.beta0_deg;
    const std::vector<std::string> files = scan_files(inputs);
    if (degeneration) {
      print_degeneration(config, files);
      return tools::kExitOk;
    }
    Segmenter segmenter(config.sensor, config.segmentation);
    SegmentationResult result;
    std::printf("sensor %s (%d x %d), beta0 %.1f deg\n", config.sensor.name.c_str(),
                config.sensor.rows, config.sensor.columns, beta0_deg);
    std::printf("%-24s %8s %8s %8s %8s %10s %8s %8s %8s %8s %8s\n", "frame", "points", "valid",
                "ground", "kept", "clusters", "proj_ms", "grnd_ms", "depth_ms", "cloud_ms",
                "total_ms");
    for (const std::string& file : files) {
      const Scan scan = read_scan_file(file);
      segmenter.project_and_mark_ground(scan, result);
      segmenter.cluster_and_build(scan, beta0_deg, result);
      const std::string name = std::filesystem::path(file).filename().string();
      const std::string problem = projection_problem(result.image.stats());
      if (!problem.empty()) {
        std::fprintf(stderr, "%s: %s; skipped\n", file.c_str(), problem.c_str());
        continue;
      }
      const StageTimes& t = result.times;
      std::printf("%-24s %8zu %8d %8d %8d %4d/%-5d %8.2f %8.2f %8.2f %8.2f %8.2f\n", name.c_str(),
                  scan.points.size(), result.image.stats().projected, result.ground_points,
                  result.clusters.kept_points(), result.clusters.kept_clusters(),
                  result.clusters.clusters(), t.get("projection"), t.get("ground"),
                  t.get("depth_clustering"), t.get("segmented_cloud"), t.total());
    }
    return tools::kExitOk;
  });
}
