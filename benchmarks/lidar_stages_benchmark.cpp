// The lidar stages on constructed sweeps (tests/support/ring_scene.hpp):
// argument 16 = VLP-16-like (28.8k points), 64 = a 64-beam variant (~135k).
#include <l2s/circle_finder.hpp>
#include <l2s/discontinuity_filter.hpp>
#include <l2s/pass_through_filter.hpp>
#include <l2s/plane_segmenter.hpp>

#include "../tests/support/ring_scene.hpp"

#include <benchmark/benchmark.h>

#include <map>

namespace {

using namespace l2s;

struct Frame {
  test::Scene scene;
  LidarCloud sweep;
  LidarCloud kept;  // after the pass-through filter
  PlaneSegmenter::Result plane;
  DiscontinuityFilter::Result edges;
};

PassThroughFilter front_box() {
  PassThroughFilter::Params box;
  box.min_xyz = Eigen::Vector3d(0.5, -4.0, -2.0);
  box.max_xyz = Eigen::Vector3d(8.0, 4.0, 2.0);
  return PassThroughFilter(box);
}

const Frame& frame(int beams) {
  static std::map<int, Frame> frames;
  auto it = frames.find(beams);
  if (it != frames.end()) return it->second;
  Frame f;
  f.scene.T_sensor_board = test::board_pose({3.0, 0.4, 0.03}, 20.0 * test::kDeg);
  f.sweep = test::scan(f.scene, beams == 64 ? test::beams64() : test::vlp16(), 1);
  f.kept = select(f.sweep, front_box().filter(f.sweep.points).kept);
  f.plane = PlaneSegmenter().segment(f.kept.points, f.scene.target);
  f.edges = DiscontinuityFilter().filter(f.kept, f.plane.plane, f.plane.inliers);
  return frames.emplace(beams, std::move(f)).first->second;
}

void BM_PassThroughFilter_Filter(benchmark::State& state) {
  const Frame& f = frame(static_cast<int>(state.range(0)));
  const PassThroughFilter filter = front_box();
  for (auto _ : state) benchmark::DoNotOptimize(filter.filter(f.sweep.points));
  state.counters["points"] = static_cast<double>(f.sweep.size());
}
BENCHMARK(BM_PassThroughFilter_Filter)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

void BM_PlaneSegmenter_Segment(benchmark::State& state) {
  const Frame& f = frame(static_cast<int>(state.range(0)));
  const PlaneSegmenter segmenter;
  for (auto _ : state) benchmark::DoNotOptimize(segmenter.segment(f.kept.points, f.scene.target));
  state.counters["points"] = static_cast<double>(f.kept.size());
}
BENCHMARK(BM_PlaneSegmenter_Segment)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_PlaneSegmenter_SegmentWholeSweep(benchmark::State& state) {
  const Frame& f = frame(static_cast<int>(state.range(0)));
  const PlaneSegmenter segmenter;
  for (auto _ : state) benchmark::DoNotOptimize(segmenter.segment(f.sweep.points, f.scene.target));
  state.counters["points"] = static_cast<double>(f.sweep.size());
}
BENCHMARK(BM_PlaneSegmenter_SegmentWholeSweep)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

/// A dense stereo-like cloud: a rows x cols ray grid in the optical frame.
void BM_PlaneSegmenter_SegmentStereo(benchmark::State& state) {
  static std::vector<Eigen::Vector3d> points;
  test::Scene scene;
  scene.T_sensor_board = test::board_pose({3.5, 0.3, 0.0}, 25.0 * test::kDeg);
  if (points.empty()) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 0.02);
    for (int row = 0; row < 800; ++row)
      for (int col = 0; col < 1280; ++col) {
        const Eigen::Vector3d d = test::ray((20.0 - 0.05 * row) * test::kDeg, (30.0 - 0.046875 * col) * test::kDeg);
        const double r = scene.cast(d);
        if (r == test::kNoHit) continue;
        const Eigen::Vector3d p = d * (r + noise(rng));
        points.emplace_back(-p.y(), -p.z(), p.x());
      }
  }
  const PlaneSegmenter segmenter(PlaneSegmenter::Params::stereo());
  for (auto _ : state) benchmark::DoNotOptimize(segmenter.segment(points, scene.target));
  state.counters["points"] = static_cast<double>(points.size());
}
BENCHMARK(BM_PlaneSegmenter_SegmentStereo)->Unit(benchmark::kMillisecond);

void BM_DiscontinuityFilter_Filter(benchmark::State& state) {
  const Frame& f = frame(static_cast<int>(state.range(0)));
  const DiscontinuityFilter filter;
  for (auto _ : state) benchmark::DoNotOptimize(filter.filter(f.kept, f.plane.plane, f.plane.inliers, Target{}));
  state.counters["edges"] = static_cast<double>(f.edges.edges.size());
}
BENCHMARK(BM_DiscontinuityFilter_Filter)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

void BM_CircleFinder_Find(benchmark::State& state) {
  const Frame& f = frame(static_cast<int>(state.range(0)));
  const CircleFinder finder;
  for (auto _ : state)
    benchmark::DoNotOptimize(finder.find(f.edges.edges, f.plane.plane, Eigen::Vector3d::UnitZ(), f.scene.target));
  state.counters["edges"] = static_cast<double>(f.edges.edges.size());
}
BENCHMARK(BM_CircleFinder_Find)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

}  // namespace
