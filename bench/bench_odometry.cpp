// Times de-skewing on a real KITTI HDL-64E frame, single thread: each point's place in the sweep
// from its azimuth (KITTI's scans carry no time field) and its move to the sweep's end, for a car
// at 27 m/s turning 2 deg a sweep.
// Run: .ws/devel/lib/adaptive_lego_loam/bench_odometry (after scripts/setup.sh)

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "adaptive_lego_loam/core/odometry/deskew.h"
#include "bench_data.h"

using namespace adaptive_lego_loam;

namespace {

using bench::kitti_frame;

void BM_Deskew(benchmark::State& state) {
  const std::vector<ScanPoint>& measured = kitti_frame().scan.points;
  const double start_azimuth = std::atan2(measured.front().y, measured.front().x);
  Eigen::Isometry3d sweep_motion = Eigen::Isometry3d::Identity();
  sweep_motion.linear() =
      Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  sweep_motion.translation() = Eigen::Vector3d(2.7, 0.05, 0.01);
  std::vector<float> fractions;
  std::vector<ScanPoint> points;
  for (auto _ : state) {
    points = measured;
    sweep_fractions(points, false, start_azimuth, 0.1, fractions);
    deskew_to_sweep_end(sweep_motion, fractions, points);
    benchmark::DoNotOptimize(points.data());
  }
  state.counters["points"] = static_cast<double>(measured.size());
}

}  // namespace

BENCHMARK(BM_Deskew)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
