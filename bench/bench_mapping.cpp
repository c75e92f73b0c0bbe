// Times the mapping's per-scan extras on a real KITTI HDL-64E frame, single thread: the wall
// patches of the vertical-structure prior, from the frame's less-flat features.
// Run: .ws/devel/lib/adaptive_lego_loam/bench_mapping (after scripts/setup.sh)

#include <benchmark/benchmark.h>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/mapping/vertical_structure.h"
#include "adaptive_lego_loam/core/odometry/feature_extraction.h"
#include "bench_data.h"

using namespace adaptive_lego_loam;

namespace {

using bench::kitti_frame;

const FeatureSet& kitti_features() {
  static const FeatureSet features = [] {
    const Config& config = kitti_frame().config;
    Segmenter segmenter(config.sensor, config.segmentation);
    SegmentationResult segmented;
    segmenter.process(kitti_frame().scan, segmented);
    FeatureExtractor extractor(config.features);
    FeatureSet out;
    extractor.extract(segmented.cloud, segmented.cloud.points, segmented.cloud.outliers, out);
    return out;
  }();
  return features;
}

void BM_WallNormals(benchmark::State& state) {
  const Cloud& less_flat = *kitti_features().less_flat;
  std::size_t normals = 0;
  for (auto _ : state) {
    normals = wall_normals(less_flat, Eigen::Matrix3d::Identity(), 5.0).size();
    benchmark::DoNotOptimize(normals);
  }
  state.counters["points"] = static_cast<double>(less_flat.size());
  state.counters["walls"] = static_cast<double>(normals);
}

}  // namespace

BENCHMARK(BM_WallNormals)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
