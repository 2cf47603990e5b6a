// Whole per-frame pipeline through the Calibrator facade on seeded simulator
// frames: both branches (run concurrently, as in production) and each alone.
#include <l2s/calibrator.hpp>
#include <l2s/sim/simulation.hpp>

#include <benchmark/benchmark.h>

#include <map>
#include <string>

namespace {

const char* lidar_name(int beams) { return beams == 64 ? "hdl64" : beams == 32 ? "hdl32" : "vlp16"; }

// One simulated frame per lidar model, made once.
const l2s::sim::DatasetSimulator& simulator(int beams) {
  static std::map<int, l2s::sim::DatasetSimulator> cache;
  auto found = cache.find(beams);
  if (found == cache.end()) {
    auto config = l2s::sim::SimulationConfig::paper(1, lidar_name(beams));
    config.frames = 1;
    config.seed = 11;
    found = cache.emplace(beams, l2s::sim::DatasetSimulator(config)).first;
  }
  return found->second;
}

void run(benchmark::State& state, bool parallel) {
  const auto& sim = simulator(static_cast<int>(state.range(0)));
  const auto frame = sim.frame(0);
  auto params = l2s::Calibrator::Params::preset(state.range(1) ? "paper" : "default");
  params.parallel_branches = parallel;
  l2s::Calibrator calibrator(sim.cameras(), sim.config().target, params);
  double lidar_ms = 0, camera_ms = 0;
  for (auto _ : state) {
    const auto report = calibrator.add(frame.lidar, frame.left, frame.right);
    lidar_ms += report.lidar.milliseconds;
    camera_ms += report.camera.milliseconds;
    if (!report.used()) state.SkipWithError("board not found");
  }
  state.counters["lidar_ms"] = lidar_ms / state.iterations();
  state.counters["camera_ms"] = camera_ms / state.iterations();
}

void BM_Calibrator_AddFrame(benchmark::State& state) { run(state, true); }
void BM_Calibrator_AddFrameSequential(benchmark::State& state) { run(state, false); }

// Args: lidar beams, preset (0 default, 1 paper).
BENCHMARK(BM_Calibrator_AddFrame)->Args({16, 0})->Args({64, 0})->Args({16, 1})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Calibrator_AddFrameSequential)->Args({16, 0})->Args({64, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
