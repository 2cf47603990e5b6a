// Simulator throughput: one lidar sweep (ideal and with a real unit's quirks),
// one rosette frame, the clean stereo render (once per dataset) for the
// paper's look and for a raw rig with shadows and every other look, per-frame
// image noise (gray and colour), and the board placement search.

#include <l2s/sim/lidar_quirks.hpp>
#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <benchmark/benchmark.h>

namespace {

using namespace l2s::sim;

const Scene& bench_scene() {
  static const Scene scene = make_scene(l2s::Target{}, BoardPose{3.0, 0.0, -0.1, 0.2, -0.06, 0.05});
  return scene;
}

LidarModel model_for(int beams) {
  return beams == 16 ? LidarModel::vlp16() : beams == 32 ? LidarModel::hdl32() : LidarModel::hdl64();
}

/// A simulator of `model`, with every quirk (laser table, beam footprint) when asked.
LidarSimulator simulator_for(const LidarModel& model, bool quirks) {
  LidarSimulator::Params params;
  params.beam_footprint = quirks;
  return LidarSimulator(quirks ? with_quirks(model, LidarQuirks::all(1)) : model, params);
}

void run_sweeps(benchmark::State& state, const LidarSimulator& lidar) {
  const RayCaster caster(bench_scene());
  const Eigen::Isometry3d T = paper_setting(8).T_cambody_lidar();
  std::uint64_t frame = 0;
  std::size_t points = 0;
  for (auto _ : state) {
    const l2s::LidarCloud cloud = lidar.sweep(caster, T, frame++);
    points = cloud.size();
    benchmark::DoNotOptimize(cloud.points.data());
  }
  state.counters["points"] = static_cast<double>(points);
}

// A spinning sweep, ideal (quirks:0) or as a real unit (quirks:1).
void BM_LidarSimulator_Sweep(benchmark::State& state) {
  run_sweeps(state, simulator_for(model_for(static_cast<int>(state.range(0))), state.range(1) != 0));
}
BENCHMARK(BM_LidarSimulator_Sweep)
    ->ArgsProduct({{16, 32, 64}, {0, 1}})
    ->ArgNames({"beams", "quirks"})
    ->Unit(benchmark::kMillisecond);

// One 0.1 s frame of a ring-free rosette lidar (mid360:0 the Avia, 1 the Mid-360).
void BM_LidarSimulator_RosetteFrame(benchmark::State& state) {
  const LidarModel model = state.range(0) == 0 ? LidarModel::avia() : LidarModel::mid360();
  run_sweeps(state, simulator_for(model, state.range(1) != 0));
}
BENCHMARK(BM_LidarSimulator_RosetteFrame)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"mid360", "quirks"})
    ->Unit(benchmark::kMillisecond);

/// 640x480, 1280x960 or 1920x1200 (the largest sensor of the randomised scenes).
StereoRig rig_of_width(int width) {
  StereoRig rig;
  rig.width = width;
  rig.height = width == 1920 ? 1200 : width * 3 / 4;
  return rig;
}

/// A raw 66 deg plumb_bob pair with wood board, brick wall, hard shadows,
/// colour, blur, vignetting and gamma: the costliest render per pixel.
StereoRenderer::Params every_look() {
  StereoRenderer::Params params;
  Appearance& look = params.appearance;
  look.board = BoardTexture::WoodGrain;
  look.background = Background::Bricks;
  look.sky = Sky::Daylight;
  look.shadows = true;
  look.colour = true;
  look.blur_sigma = 1.0;
  look.vignetting = 0.3;
  look.gamma = 2.2;
  return params;
}

StereoRig raw_rig_of_width(int width) {
  StereoRig rig = rig_of_width(width);
  rig.horizontal_fov = 66.0 * 3.141592653589793 / 180.0;
  return rig.with_real_lenses(DistortionModel::PlumbBob);
}

void BM_StereoRenderer_RenderPair(benchmark::State& state) {
  const RayCaster caster(bench_scene());
  const StereoRenderer renderer(rig_of_width(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    const CleanStereo clean = renderer.render(caster);
    benchmark::DoNotOptimize(clean.left.intensity.data());
  }
}
BENCHMARK(BM_StereoRenderer_RenderPair)->Arg(640)->Arg(1280)->Arg(1920)->Unit(benchmark::kMillisecond);

void BM_StereoRenderer_RenderPairRawShadowsColour(benchmark::State& state) {
  const RayCaster caster(bench_scene());
  const StereoRenderer renderer(raw_rig_of_width(static_cast<int>(state.range(0))), every_look());
  for (auto _ : state) {
    const CleanStereo clean = renderer.render(caster);
    benchmark::DoNotOptimize(clean.left.intensity.data());
  }
}
BENCHMARK(BM_StereoRenderer_RenderPairRawShadowsColour)->Arg(1280)->Arg(1920)->Unit(benchmark::kMillisecond);

void BM_StereoRenderer_AddNoise(benchmark::State& state) {
  const StereoRenderer renderer(rig_of_width(static_cast<int>(state.range(0))));
  const CleanStereo clean = renderer.render(RayCaster(bench_scene()));
  std::uint64_t frame = 0;
  for (auto _ : state) {
    const StereoImages images = renderer.add_noise(clean, 1.0, 1, frame++);
    benchmark::DoNotOptimize(images.left.pixels.data());
  }
}
BENCHMARK(BM_StereoRenderer_AddNoise)->Arg(1280)->Arg(1920)->Unit(benchmark::kMillisecond);

void BM_StereoRenderer_AddNoiseColour(benchmark::State& state) {
  const StereoRenderer renderer(raw_rig_of_width(static_cast<int>(state.range(0))), every_look());
  const CleanStereo clean = renderer.render(RayCaster(bench_scene()));
  std::uint64_t frame = 0;
  for (auto _ : state) {
    const StereoImages images = renderer.add_noise(clean, 1.0, 1, frame++);
    benchmark::DoNotOptimize(images.left.pixels.data());
  }
}
BENCHMARK(BM_StereoRenderer_AddNoiseColour)->Arg(1280)->Arg(1920)->Unit(benchmark::kMillisecond);

void BM_FindPlacement_AllModels(benchmark::State& state) {
  const std::vector<LidarModel> models{LidarModel::vlp16(), LidarModel::hdl32(), LidarModel::hdl64()};
  const SensorSetting setting = paper_setting(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const PlacementResult result = find_placement(l2s::Target{}, setting, models);
    benchmark::DoNotOptimize(result.score);
  }
}
BENCHMARK(BM_FindPlacement_AllModels)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);

}  // namespace
