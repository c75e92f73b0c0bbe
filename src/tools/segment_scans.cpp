// Segments scans as LeGO-LOAM's imageProjection does (projection, ground, depth clustering with
// one beta0) and prints per frame what was kept and how long each stage took.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/scan_files.h"
#include "tool_main.h"

using namespace adaptive_lego_loam;

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
  app.add_option("inputs", inputs, "scan files (.bin, .pcd) or folders of them")->required();
  if (const auto status = tools::parse_command_line(app, argc, argv, "segment_scans")) {
    return *status;
  }
  return tools::run_job("segment_scans", [&] {
    const Config config = load_config(config_path);
    if (beta0_deg < 0) beta0_deg = config.segmentation.beta0_deg;
    std::vector<std::string> files;
    for (const std::string& input : inputs) {
      if (std::filesystem::is_directory(input)) {
        for (const std::string& file : list_scan_files(input))
          files.push_back(file);
      } else {
        files.push_back(input);
      }
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
