#include "adaptive_lego_loam/core/clustering/segmenter.h"

#include "adaptive_lego_loam/core/projection/ground.h"

namespace adaptive_lego_loam {

Segmenter::Segmenter(const SensorParams& sensor, const SegmentationParams& params)
    : sensor_(sensor), params_(params), projector_(sensor), depth_(projector_.geometry()) {}

void Segmenter::project_and_mark_ground(const Scan& scan, SegmentationResult& result) {
  Stopwatch watch;
  projector_.project(scan, result.image);
  result.times.clear();
  result.times.add("projection", watch.lap_ms());
  result.ground_points =
      mark_ground(result.image, sensor_.ground_rows, sensor_.mount_angle_deg,
                  params_.ground_slope_tolerance_deg, result.ground, params_.ground_row_gap_deg);
  result.times.add("ground", watch.lap_ms());
}

void Segmenter::cluster_and_build(const Scan& scan, double beta0_deg, SegmentationResult& result) {
  Stopwatch watch;
  depth_.cluster(result.image, result.ground, beta0_deg, params_.size_rule, result.clusters);
  result.beta0_deg = beta0_deg;
  result.times.add("depth_clustering", watch.lap_ms());
  build_cloud(scan, result);
}

void Segmenter::build_cloud(const Scan& scan, SegmentationResult& result) const {
  Stopwatch watch;
  build_segmented_cloud(result.image, result.ground, result.clusters, params_, sensor_.ground_rows,
                        result.cloud);
  sweep_orientation(scan, result.cloud.info);
  result.times.add("segmented_cloud", watch.lap_ms());
}

void Segmenter::process(const Scan& scan, SegmentationResult& result) {
  project_and_mark_ground(scan, result);
  cluster_and_build(scan, params_.beta0_deg, result);
}

}  // namespace adaptive_lego_loam
