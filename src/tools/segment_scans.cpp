// Segments scans as LeGO-LOAM's imageProjection does (projection, ground, depth clustering with
// one beta0) and prints per frame what was kept and how long each stage took; or, with
// --degeneration, the degeneration degree mu as the ambient filter finds it on the range image and
// as a KD-tree over every non-ground point finds it (the paper's Fig. 8), with their times.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/projection/config_fit.h"
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

// Per point of `scan`: 0 not in the range image (invalid, out of range, lost its cell), 1 ground,
// 2 in a kept cluster, 3 in a dropped one; written as one byte a point to DIR/<scan name>.flags.
void write_point_flags(const std::string& dir, const std::string& file, const Scan& scan,
                       const SegmentationResult& result) {
  std::vector<uint8_t> flags(scan.points.size(), 0);
  const RangeImage& image = result.image;
  for (int cell = 0; cell < image.size(); ++cell) {
    if (!image.occupied(cell)) continue;
    flags[image.source_index(cell)] =
        result.ground[cell] ? 1 : (result.clusters.point_kept(cell) ? 2 : 3);
  }
  const std::filesystem::path path =
      std::filesystem::path(dir) / (std::filesystem::path(file).stem().string() + ".flags");
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(flags.data()),
            static_cast<std::streamsize>(flags.size()));
  if (!out) throw IoError(path.string() + ": cannot write");
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
  bool adaptive = false;
  app.add_flag("--adaptive", adaptive, "the adaptive beta0 of the ambient filter instead")
      ->excludes("--beta0");
  std::string flags_dir;
  app.add_option("--point-flags", flags_dir,
                 "write per scan a byte per point to DIR/<scan>.flags: 0 not projected, 1 ground, "
                 "2 kept, 3 dropped");
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
    if (!flags_dir.empty()) std::filesystem::create_directories(flags_dir);
    Config filter_config = config;
    filter_config.ambient.mode = adaptive ? Beta0Mode::kAdaptive : Beta0Mode::kFixed;
    filter_config.ambient.fixed_beta0_deg = beta0_deg;
    AmbientFilter filter(filter_config);
    AmbientFilterResult filtered;
    const SegmentationResult& result = filtered.segmentation;
    char threshold[32] = "adaptive";
    if (!adaptive) std::snprintf(threshold, sizeof(threshold), "%.1f deg", beta0_deg);
    std::printf("sensor %s (%d x %d), beta0 %s\n", config.sensor.name.c_str(), config.sensor.rows,
                config.sensor.columns, threshold);
    std::printf("%-24s %8s %8s %8s %8s %10s %8s %8s %8s %8s %8s\n", "frame", "points", "valid",
                "ground", "kept", "clusters", "proj_ms", "grnd_ms", "depth_ms", "cloud_ms",
                "total_ms");
    ConfigFitWarning fit(config_path, files.size() == 1 ? files.front() : "these scans");
    for (const std::string& file : files) {
      const Scan scan = read_scan_file(file);
      filter.process(scan, filtered);
      if (const auto warning = fit.check(config.sensor, result.image,
                                         rows_from_ring(config.sensor, scan.has_ring))) {
        std::fprintf(stderr, "segment_scans: warning: %s\n", warning->c_str());
      }
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
      if (!flags_dir.empty()) write_point_flags(flags_dir, file, scan, result);
    }
    return tools::kExitOk;
  });
}
