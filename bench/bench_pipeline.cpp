// Times whole scans through every stage of the pipeline (as run_sequence runs them, one thread,
// the configs as shipped): real KITTI HDL-64E scans (sequence 07's first five, test/data,
// config/kitti.yaml) and a simulated VLP-16 urban drive (lidar_sim's urban scenario, default
// foliage, config/vlp16.yaml). The first scan pair (its start search from several guesses) is
// timed apart from the scans after it, and the scans after it with two threads (wall clock).
// Each iteration starts a new pipeline: the time is the mean of the timed scans, so a change that
// costs time shows here.
// Run: .ws/devel/lib/adaptive_lego_loam/bench_pipeline (after scripts/setup.sh)

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/timing.h"
#include "adaptive_lego_loam/core/pipeline/pipeline.h"
#include "adaptive_lego_loam/sim/scenario.h"
#include "adaptive_lego_loam/sim/simulator.h"
#include "bench_data.h"

using namespace adaptive_lego_loam;

namespace {

struct Drive {
  Config config;
  std::vector<Scan> scans;
};

const Drive& kitti_drive() {
  static const Drive drive = [] {
    Drive kitti{bench::kitti_frame().config, {}};
    for (int frame = 0; frame < 5; ++frame) {
      kitti.scans.push_back(read_kitti_bin(std::string(PROJECT_SOURCE_DIR) +
                                           "/test/data/kitti_seq07/velodyne/000000000" +
                                           std::to_string(frame) + ".bin"));
    }
    return kitti;
  }();
  return drive;
}

const Drive& vlp16_drive() {
  static const Drive drive = [] {
    Drive vlp16{load_config(std::string(PROJECT_SOURCE_DIR) + "/config/vlp16.yaml"), {}};
    sim::SceneRequest request;
    request.scenario = sim::named_scenario("urban");
    request.frames = 12;
    request.frame_period = vlp16.config.sensor.scan_period;
    request.reach = vlp16.config.sensor.max_range;
    const sim::GeneratedScene scene = sim::generate_scene(request);
    sim::LidarSimulator simulator(sim::LidarModel(vlp16.config.sensor, sim::SimSensorOptions()),
                                  scene.world, scene.trajectory, request.seed);
    for (int frame = 0; frame < request.frames; ++frame)
      vlp16.scans.push_back(simulator.render(frame).scan);
    return vlp16;
  }();
  return drive;
}

// Scans [first, last) of a new pipeline timed in thread CPU time (run_sequence --cpu-time's
// clock), those before it run untimed; the iteration's time is their mean.
void time_scans(benchmark::State& state, const Drive& drive, std::size_t first, std::size_t last) {
  for (auto _ : state) {
    Pipeline pipeline(drive.config);
    for (std::size_t i = 0; i < first; ++i)
      pipeline.process(drive.scans[i]);
    const Stopwatch watch(Clock::kThreadCpu);
    for (std::size_t i = first; i < last; ++i)
      benchmark::DoNotOptimize(pipeline.process(drive.scans[i]).pose);
    state.SetIterationTime(watch.elapsed_ms() / 1000.0 / static_cast<double>(last - first));
  }
  state.counters["scans"] = static_cast<double>(last - first);
}

// The same with two threads (Pipeline::set_threads, each scan processed knowing the next, as
// run_sequence --threads 2): wall-clock time, the throughput on an otherwise idle machine.
void time_scans_two_threads(benchmark::State& state, const Drive& drive, std::size_t first,
                            std::size_t last) {
  for (auto _ : state) {
    Pipeline pipeline(drive.config);
    pipeline.set_threads(2);
    const auto next = [&](std::size_t i) {
      return i + 1 < drive.scans.size() ? &drive.scans[i + 1] : nullptr;
    };
    for (std::size_t i = 0; i < first; ++i)
      pipeline.process(drive.scans[i], next(i));
    const Stopwatch watch(Clock::kWall);
    for (std::size_t i = first; i < last; ++i)
      benchmark::DoNotOptimize(pipeline.process(drive.scans[i], next(i)).pose);
    state.SetIterationTime(watch.elapsed_ms() / 1000.0 / static_cast<double>(last - first));
  }
  state.counters["scans"] = static_cast<double>(last - first);
}

void BM_KittiFirstScanPair(benchmark::State& state) {
  time_scans(state, kitti_drive(), 0, 2);
}

void BM_KittiScan(benchmark::State& state) {
  time_scans(state, kitti_drive(), 2, kitti_drive().scans.size());
}

void BM_Vlp16FirstScanPair(benchmark::State& state) {
  time_scans(state, vlp16_drive(), 0, 2);
}

void BM_Vlp16Scan(benchmark::State& state) {
  time_scans(state, vlp16_drive(), 2, vlp16_drive().scans.size());
}

void BM_KittiScanTwoThreadsWall(benchmark::State& state) {
  time_scans_two_threads(state, kitti_drive(), 2, kitti_drive().scans.size());
}

void BM_Vlp16ScanTwoThreadsWall(benchmark::State& state) {
  time_scans_two_threads(state, vlp16_drive(), 2, vlp16_drive().scans.size());
}

}  // namespace

BENCHMARK(BM_KittiFirstScanPair)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KittiScan)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Vlp16FirstScanPair)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Vlp16Scan)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KittiScanTwoThreadsWall)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Vlp16ScanTwoThreadsWall)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
