// Times the ambient-aware filter's stages on a real KITTI HDL-64E scan, single thread, and the
// KD-tree baseline for the degeneration degree (the paper's Fig. 8 comparison).
// Run: .ws/devel/lib/adaptive_lego_loam/bench_ambient_filter (after scripts/setup.sh)

#include <benchmark/benchmark.h>

#include <climits>

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"
#include "adaptive_lego_loam/core/ambient/kdtree_normals.h"
#include "adaptive_lego_loam/core/ambient/skeleton.h"
#include "bench_data.h"

using namespace adaptive_lego_loam;
using bench::kitti_frame;

namespace {

// Projection and ground, done once: the stages below start from them.
const SegmentationResult& projected() {
  static const SegmentationResult result = [] {
    SegmentationResult r;
    Segmenter(kitti_frame().config.sensor, kitti_frame().config.segmentation)
        .project_and_mark_ground(kitti_frame().scan, r);
    return r;
  }();
  return result;
}

void BM_AdaptiveEuclideanClustering(benchmark::State& state) {
  const Config& config = kitti_frame().config;
  EuclideanClustering clustering(
      projected().image.geometry(),
      euclidean_params(config.ambient, config.ambient.skeleton_euclidean_min_points));
  ClusterLabels labels;
  for (auto _ : state) {
    clustering.cluster(projected().image, projected().ground, labels);
    benchmark::DoNotOptimize(labels.clusters());
  }
}

// Steps 5-7: strict depth clusters, skeleton, normals and mu (Euclidean labels given).
void BM_SkeletonNormalsMu(benchmark::State& state) {
  const Config& config = kitti_frame().config;
  const AmbientFilterParams& ambient = config.ambient;
  const RangeImage& image = projected().image;
  ClusterLabels euclidean, depth;
  EuclideanClustering(image.geometry(),
                      euclidean_params(ambient, ambient.skeleton_euclidean_min_points))
      .cluster(image, projected().ground, euclidean);
  DepthClustering strict(image.geometry());
  std::vector<uint8_t> skeleton;
  std::vector<NormalFeature> normals;
  const NormalParams params = normal_params(ambient, config.sensor.max_range);
  for (auto _ : state) {
    strict.cluster(image, projected().ground, ambient.beta0_max_deg,
                   {ambient.skeleton_depth_min_points, INT_MAX, INT_MAX}, depth);
    extract_skeleton(euclidean, depth, skeleton);
    compute_normals(image, skeleton, projected().ground, params, normals);
    benchmark::DoNotOptimize(degeneration_from_normals(normals).mu);
  }
  state.SetLabel("normals=" + std::to_string(normals.size()));
}

// Steps 1-9 on the raw scan.
void BM_AmbientFilterTotal(benchmark::State& state) {
  AmbientFilter filter(kitti_frame().config);
  AmbientFilterResult result;
  for (auto _ : state) {
    filter.process(kitti_frame().scan, result);
    benchmark::ClobberMemory();  // (DoNotOptimize on a double lvalue corrupts it in
                                 // benchmark 1.7.1)
  }
  // Debian's libbenchmark garbles fractional counters: report through the label.
  state.SetLabel("mu=" + std::to_string(result.mu) +
                 " beta0_deg=" + std::to_string(result.beta0_deg) +
                 " skeleton=" + std::to_string(result.skeleton_points));
}

// Range-image mu from the skeleton, from the projected image (= skeleton + normals + mu + the
// Euclidean clustering it needs), to compare with the KD-tree mu below.
void BM_RangeImageMu(benchmark::State& state) {
  AmbientFilter filter(kitti_frame().config);
  AmbientFilterResult result;
  filter.process(kitti_frame().scan, result);
  for (auto _ : state) {
    filter.process(kitti_frame().scan, result);
    const StageTimes& t = result.times();
    state.SetIterationTime((t.get("euclidean_clustering") + t.get("skeleton") + t.get("normals") +
                            t.get("degeneration")) /
                           1000.0);
  }
  state.SetLabel("mu=" + std::to_string(result.mu));
}

// The paper's baseline: normals of every non-ground point by KD-tree radius search, then mu.
void BM_KdTreeMu(benchmark::State& state) {
  const Config& config = kitti_frame().config;
  const std::vector<ScanPoint> points = non_ground_points(projected());
  const KdTreeNormalParams params = kdtree_normal_params(config);
  std::vector<NormalFeature> normals;
  double mu = 0.0;
  for (auto _ : state) {
    kdtree_normals(points, params, normals);
    mu = degeneration_from_normals(normals).mu;
    benchmark::ClobberMemory();
  }
  state.SetLabel("mu=" + std::to_string(mu) + " normals=" + std::to_string(normals.size()) +
                 " points=" + std::to_string(points.size()));
}

}  // namespace

BENCHMARK(BM_AdaptiveEuclideanClustering)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SkeletonNormalsMu)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AmbientFilterTotal)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RangeImageMu)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTreeMu)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
