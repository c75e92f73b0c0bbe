// Place recognition's cost per keyframe: the descriptor of a keyframe's features, and the
// candidate search over a long run's places. On a real VLP-16 frame (test/data), whose raw
// points stand in for a keyframe's features (a keyframe holds fewer).

#include <benchmark/benchmark.h>

#include <random>

#include "adaptive_lego_loam/core/loop_closure/place_recognition.h"
#include "adaptive_lego_loam/io/scan_files.h"

using namespace adaptive_lego_loam;

namespace {

const Cloud& vlp16_points() {
  static const Cloud cloud = [] {
    const Scan scan =
        read_scan_file(std::string(PROJECT_SOURCE_DIR) + "/test/data/vlp16/vlp16_indoor.pcd");
    Cloud points;
    for (const ScanPoint& p : scan.points) {
      CloudPoint q;
      q.x = p.x;
      q.y = p.y;
      q.z = p.z;
      points.push_back(q);
    }
    return points;
  }();
  return cloud;
}

Eigen::Isometry3d turned(double yaw, double x) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation().x() = x;
  return pose;
}

void BM_PlaceDescriptor(benchmark::State& state) {
  const PlaceRecognition places{LoopClosureParams()};
  const Cloud& points = vlp16_points();
  for (auto _ : state)
    benchmark::DoNotOptimize(places.describe({&points}, Eigen::Isometry3d::Identity()));
  state.counters["points"] = points.size();
}

// The candidate search of the newest keyframe among `places` older ones: the same frame seen
// turned and moved, so that every ring key is near and the full comparisons all run.
void BM_PlaceCandidate(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  LoopClosureParams params;
  PlaceRecognition places(params);
  std::mt19937 random(1);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), x(-3.0, 3.0);
  std::vector<Keyframe> keyframes(count + 1);
  for (int i = 0; i <= count; ++i) {
    keyframes[i].index = i;
    keyframes[i].stamp = i;
    keyframes[i].pose = turned(yaw(random), x(random));
    Cloud moved = *transform_cloud(vlp16_points(), keyframes[i].pose.inverse());
    places.add(i, keyframes[i].stamp, places.describe({&moved}, Eigen::Isometry3d::Identity()));
  }
  keyframes[count].stamp = count + 100.0;
  for (auto _ : state)
    benchmark::DoNotOptimize(places.candidate(keyframes, count));
  state.counters["places"] = count;
}

}  // namespace

BENCHMARK(BM_PlaceDescriptor)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlaceCandidate)->Arg(1500)->Arg(15000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
