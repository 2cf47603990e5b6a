// Camera-side stages and registration on one rendered 1280x960 frame: the
// board of the default target 3 m ahead, yawed 10 deg, in front of a wall.
#include <l2s/board_pose_refiner.hpp>
#include <l2s/circle_finder.hpp>
#include <l2s/edge_filter.hpp>
#include <l2s/registrar.hpp>
#include <l2s/stereo_matcher.hpp>

#include "../tests/support/board_renderer.hpp"

#include <benchmark/benchmark.h>

namespace {

struct Frame {
  l2s::test::BoardScene scene;
  l2s::test::StereoPair pair;
  l2s::StereoCloud board;
  l2s::Plane plane;
};

const Frame& frame() {
  static const Frame f = [] {
    Frame f;
    f.scene.camera = l2s::test::make_stereo_camera();
    f.scene.T_camera_board = l2s::test::board_pose(3.0, 10.0 * M_PI / 180.0, 0.0, 0.1);
    f.scene.noise_sigma = 0.007;
    f.pair = l2s::test::render_pair(f.scene);
    const Eigen::Vector3d n = f.scene.T_camera_board.linear().col(2);
    f.plane = l2s::Plane(n, -n.dot(f.scene.T_camera_board.translation()));
    const auto stereo = l2s::StereoMatcher().match(f.pair.left, f.pair.right, f.scene.camera);
    for (std::size_t k = 0; k < stereo.cloud.size(); ++k)
      if (f.plane.absDistance(stereo.cloud.points[k]) < 0.02) {
        f.board.points.push_back(stereo.cloud.points[k]);
        f.board.pixels.push_back(stereo.cloud.pixels[k]);
      }
    return f;
  }();
  return f;
}

/// Args: downscale in percent, nearest depth searched in cm (the farthest is 10 m).
void BM_StereoMatcher_Match(benchmark::State& state) {
  const Frame& f = frame();
  l2s::StereoMatcher::Params params;
  params.downscale = state.range(0) / 100.0;
  params.min_depth = state.range(1) / 100.0;
  const l2s::StereoMatcher matcher(params);
  double sgbm_ms = 0.0;
  for (auto _ : state) {
    const auto result = matcher.match(f.pair.left, f.pair.right, f.scene.camera);
    sgbm_ms += result.match_ms;
    benchmark::DoNotOptimize(result.cloud.points.data());
  }
  state.counters["sgbm_ms"] = benchmark::Counter(sgbm_ms, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_StereoMatcher_Match)->Args({100, 100})->Args({100, 200})->Args({50, 100})->Unit(benchmark::kMillisecond);

void BM_EdgeFilter_Filter(benchmark::State& state) {
  const Frame& f = frame();
  const l2s::EdgeFilter filter;
  for (auto _ : state) {
    const auto result = filter.filter(f.pair.left, f.scene.camera.left, f.board, f.plane, f.scene.target);
    benchmark::DoNotOptimize(result.edges.points.data());
  }
  state.counters["points_in"] = static_cast<double>(f.board.size());
}
BENCHMARK(BM_EdgeFilter_Filter)->Unit(benchmark::kMillisecond);

/// The camera's circle search on the filtered edges of the frame (the
/// default preset's: candidates, then the whole pattern's votes when the
/// candidates do not form it).
void BM_CircleFinder_FindCamera(benchmark::State& state) {
  const Frame& f = frame();
  const auto edges = l2s::EdgeFilter().filter(f.pair.left, f.scene.camera.left, f.board, f.plane, f.scene.target);
  const l2s::CircleFinder finder;
  const Eigen::Vector3d up_optical(0.0, -1.0, 0.0);
  for (auto _ : state) {
    const auto result = finder.find(edges.edges.points, f.plane, up_optical, f.scene.target, edges.gradients);
    if (!result.found) state.SkipWithError(("circles not found: " + result.reason).c_str());
    benchmark::DoNotOptimize(result.centers);
  }
  state.counters["edge_points"] = static_cast<double>(edges.edges.size());
}
BENCHMARK(BM_CircleFinder_FindCamera)->Unit(benchmark::kMillisecond);

void BM_BoardPoseRefiner_Refine(benchmark::State& state) {
  const Frame& f = frame();
  Eigen::Isometry3d start = f.scene.T_camera_board;
  start.linear() = Eigen::AngleAxisd(0.026, Eigen::Vector3d(0.7, 0.6, 0.2).normalized()) * start.linear();
  start.translation() += Eigen::Vector3d(0.003, -0.002, 0.0035);
  l2s::BoardPoseRefiner::Params params;
  params.fit_board_outline = state.range(0) != 0;  // /0: the hole rims alone, /1: with the board's outline (default)
  const l2s::BoardPoseRefiner refiner(params);
  for (auto _ : state) {
    const auto result = refiner.refine(f.pair.left, f.pair.right, f.scene.camera, f.scene.target, start);
    benchmark::DoNotOptimize(result.T_camera_board);
  }
}
BENCHMARK(BM_BoardPoseRefiner_Refine)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_Registrar_Estimate(benchmark::State& state) {
  const l2s::HoleCenters camera = {Eigen::Vector3d(-0.25, -0.2, 3.0), Eigen::Vector3d(0.25, -0.2, 3.0),
                                   Eigen::Vector3d(-0.25, 0.2, 3.0), Eigen::Vector3d(0.25, 0.2, 3.0)};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.67, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.1, -0.3, 0.2);
  l2s::HoleCenters lidar;
  for (int i = 0; i < 4; ++i) lidar[i] = T * camera[i];
  const l2s::Registrar registrar;
  for (auto _ : state) benchmark::DoNotOptimize(registrar.estimate(lidar, camera).T_lidar_camera);
}
BENCHMARK(BM_Registrar_Estimate);

}  // namespace
