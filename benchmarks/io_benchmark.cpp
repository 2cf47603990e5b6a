// Data in: ring recovery (it runs per frame for sweeps without a ring field)
// and rectification of raw image pairs, on seeded synthetic data
// (tests/support/laser_sweep.hpp: beams from their own origins, as in real
// calibration tables). Argument 16 = VLP-16-like, 64 = HDL-64E-like.
#include <l2s/io/ring_recovery.hpp>
#include <l2s/stereo_rectifier.hpp>

#include "../tests/support/laser_sweep.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace l2s;

test::LaserTable table(int beams) {
  return beams == 64 ? test::hdl64e_table() : test::vlp16_table();
}

// ~120k returns for 64 beams (1875 per laser, ranges 0.2-60 m), 28.8k for 16.
LidarCloud random_sweep(int beams) {
  test::SweepOptions options;
  options.points_per_laser = beams == 64 ? 1875 : 1800;
  return test::laser_sweep(table(beams), options).cloud;
}

// A corridor swept every 0.17 deg (64 beams: 135k returns) or 0.2 deg (16: 28.8k).
test::OrganisedSweep corridor(int beams) {
  test::CorridorOptions options;
  options.azimuth_step_deg = beams == 64 ? 0.17 : 0.2;
  return test::corridor_sweep(table(beams), options);
}

void BM_RingRecovery_RandomRanges(benchmark::State& state) {
  const LidarCloud sweep = random_sweep(static_cast<int>(state.range(0)));
  int rings = 0;
  for (auto _ : state) {
    LidarCloud cloud = sweep;  // the copy is part of a frame's cost, and small
    rings = io::recover_ring_structure(cloud).rings;
  }
  state.counters["points"] = static_cast<double>(sweep.size());
  state.counters["rings"] = rings;
}
BENCHMARK(BM_RingRecovery_RandomRanges)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_RingRecovery_Corridor(benchmark::State& state) {
  const test::OrganisedSweep sweep = corridor(static_cast<int>(state.range(0)));
  int rings = 0;
  for (auto _ : state) {
    LidarCloud cloud = sweep.cloud;
    rings = io::recover_ring_structure(cloud).rings;
  }
  state.counters["points"] = static_cast<double>(sweep.cloud.size());
  state.counters["rings"] = rings;
}
BENCHMARK(BM_RingRecovery_Corridor)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_RingRecovery_OrganisedRows(benchmark::State& state) {
  const test::OrganisedSweep sweep = corridor(static_cast<int>(state.range(0)));
  int rings = 0;
  for (auto _ : state) {
    LidarCloud cloud = sweep.cloud;
    rings = io::rings_from_rows(cloud, sweep.rows).rings;
  }
  state.counters["points"] = static_cast<double>(sweep.cloud.size());
  state.counters["rings"] = rings;
}
BENCHMARK(BM_RingRecovery_OrganisedRows)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

// A 1280x960 gray pair, plumb_bob, R of a degree.
void BM_StereoRectifier_Rectify(benchmark::State& state) {
  StereoCamera raw;
  raw.images = ImageKind::Raw;
  raw.left = CameraInfo::ideal("left", 1280, 960, 985.0, 639.5, 479.5);
  raw.right = CameraInfo::ideal("right", 1280, 960, 985.0, 639.5, 479.5, 0.12);
  for (CameraInfo* camera : {&raw.left, &raw.right}) {
    camera->distortion_coefficients = {-0.25, 0.08, 0.0005, -0.0003, 0.0};
    camera->rectification_matrix =
        Eigen::AngleAxisd(0.017, Eigen::Vector3d(0.3, 1.0, 0.1).normalized()).toRotationMatrix();
  }
  const StereoRectifier rectifier(raw);
  Image left(1280, 960, 1), right(1280, 960, 1);
  for (std::size_t i = 0; i < left.pixels.size(); ++i)
    left.pixels[i] = right.pixels[i] = static_cast<std::uint8_t>((i * 2654435761u) >> 24);
  for (auto _ : state) benchmark::DoNotOptimize(rectifier.rectify(left, right));
}
BENCHMARK(BM_StereoRectifier_Rectify)->Unit(benchmark::kMillisecond);

}  // namespace
