// Times the range-image stages on a real KITTI HDL-64E frame, single thread.
// Run: .ws/devel/lib/adaptive_lego_loam/bench_segmentation (after scripts/setup.sh)

#include <benchmark/benchmark.h>

#include "adaptive_lego_loam/core/clustering/depth_clustering.h"
#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/ground.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "bench_data.h"

using namespace adaptive_lego_loam;

namespace {

using bench::kitti_frame;

void BM_Projection(benchmark::State& state) {
  RangeProjector projector(kitti_frame().config.sensor);
  RangeImage image;
  for (auto _ : state) {
    projector.project(kitti_frame().scan, image);
    benchmark::DoNotOptimize(image.stats().projected);
  }
}

void BM_Ground(benchmark::State& state) {
  const SensorParams& sensor = kitti_frame().config.sensor;
  RangeImage image;
  RangeProjector(sensor).project(kitti_frame().scan, image);
  std::vector<uint8_t> ground;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        mark_ground(image, sensor.ground_rows, sensor.mount_angle_deg,
                    kitti_frame().config.segmentation.ground_slope_tolerance_deg, ground));
  }
}

void BM_DepthClustering(benchmark::State& state) {
  const Config& config = kitti_frame().config;
  RangeProjector projector(config.sensor);
  RangeImage image;
  projector.project(kitti_frame().scan, image);
  std::vector<uint8_t> ground;
  mark_ground(image, config.sensor.ground_rows, config.sensor.mount_angle_deg,
              config.segmentation.ground_slope_tolerance_deg, ground);
  DepthClustering clustering(projector.geometry());
  ClusterLabels labels;
  for (auto _ : state) {
    clustering.cluster(image, ground, static_cast<double>(state.range(0)),
                       config.segmentation.size_rule, labels);
    benchmark::DoNotOptimize(labels.clusters());
  }
}

// Projection + ground + depth clustering + segmented cloud, as imageProjection runs them.
void BM_SegmentationTotal(benchmark::State& state) {
  Segmenter segmenter(kitti_frame().config.sensor, kitti_frame().config.segmentation);
  SegmentationResult result;
  for (auto _ : state) {
    segmenter.process(kitti_frame().scan, result);
    benchmark::DoNotOptimize(result.cloud.points.size());
  }
}

}  // namespace

BENCHMARK(BM_Projection)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ground)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DepthClustering)->Arg(10)->Arg(60)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SegmentationTotal)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
