// Concurrency (run under ThreadSanitizer by scripts/sanitize.sh): what the
// headers promise about threads. Separate Calibrators in separate threads,
// one const Calibrator's camera_branch() from several threads and beside its
// add(), the simulator's const frame() from several threads, and atomic
// writes of one file from two threads. Each threaded result must equal the
// one-thread result.

#include <l2s/calibrator.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/sim/simulation.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace l2s {
namespace {

constexpr int kFrames = 2;

// Two frames keep the test quick under ThreadSanitizer (5-15x slower).
sim::SimulationConfig config() {
  auto config = sim::SimulationConfig::paper(8, "vlp16");
  config.frames = kFrames;
  config.seed = 11;
  config.threads = 2;  // the simulator's own worker threads run too
  return config;
}

const sim::DatasetSimulator& simulator() {
  static const sim::DatasetSimulator instance(config());
  return instance;
}

const std::vector<sim::SimulatedFrame>& frames() {
  static const std::vector<sim::SimulatedFrame> all = [] {
    std::vector<sim::SimulatedFrame> out;
    for (int i = 0; i < kFrames; ++i) out.push_back(simulator().frame(i));
    return out;
  }();
  return all;
}

Calibrator::Result calibrate(const std::string& preset) {
  Calibrator calibrator(simulator().cameras(), simulator().config().target, Calibrator::Params::preset(preset));
  for (const auto& frame : frames()) calibrator.add(frame.lidar, frame.left, frame.right);
  return calibrator.result();
}

void expect_same(const Calibrator::Result& a, const Calibrator::Result& b) {
  EXPECT_EQ(a.found, b.found);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.lidar_frames, b.lidar_frames);
  EXPECT_EQ(a.camera_frames, b.camera_frames);
  EXPECT_TRUE(a.T_lidar_camera.isApprox(b.T_lidar_camera, 1e-12));
}

TEST(Concurrency, TwoCalibratorsInTwoThreadsGiveTheOneThreadResults) {
  const Calibrator::Result paper = calibrate("paper");
  const Calibrator::Result fine = calibrate("default");
  ASSERT_TRUE(paper.found) << paper.reason;
  EXPECT_POSE_NEAR(paper.T_lidar_camera, simulator().T_lidar_camera(), 1.0, 0.05);

  Calibrator::Result threaded[2];
  // Each calibrator runs its two branches concurrently as well (parallel_branches).
  std::thread first([&] { threaded[0] = calibrate("paper"); });
  std::thread second([&] { threaded[1] = calibrate("default"); });
  first.join();
  second.join();
  expect_same(threaded[0], paper);
  expect_same(threaded[1], fine);
}

TEST(Concurrency, CameraBranchOfOneCalibratorFromTwoThreads) {
  const Calibrator calibrator(simulator().cameras(), simulator().config().target,
                              Calibrator::Params::preset("paper"));
  const auto& frame = frames()[0];
  const BranchReport alone = calibrator.camera_branch(frame.left, frame.right);
  BranchReport reports[2];
  std::thread first([&] { reports[0] = calibrator.camera_branch(frame.left, frame.right); });
  std::thread second([&] { reports[1] = calibrator.camera_branch(frame.left, frame.right); });
  first.join();
  second.join();
  for (const auto& report : reports) {
    EXPECT_EQ(report.found, alone.found);
    EXPECT_EQ(report.reason, alone.reason);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(report.centers[i], alone.centers[i]);
  }
}

// What `l2s calibrate` does: the next frame's camera branch on a worker
// while add() accumulates the frame before (default preset: the scene check
// measures the kept frames' edges in add()).
TEST(Concurrency, CameraBranchAheadWhileAddRuns) {
  Calibrator sequential(simulator().cameras(), simulator().config().target);
  for (const auto& frame : frames()) sequential.add(frame.lidar, frame.left, frame.right);
  Calibrator pipelined(simulator().cameras(), simulator().config().target);
  BranchReport current = pipelined.camera_branch(frames()[0].left, frames()[0].right);
  for (int i = 0; i < kFrames; ++i) {
    BranchReport next;
    std::thread ahead([&] {
      if (i + 1 < kFrames) next = pipelined.camera_branch(frames()[i + 1].left, frames()[i + 1].right);
    });
    pipelined.add(frames()[i].lidar, current);
    ahead.join();
    current = next;
  }
  const auto expected = sequential.result();
  const auto got = pipelined.result();
  ASSERT_EQ(got.found, expected.found) << got.reason;
  EXPECT_TRUE(got.T_lidar_camera.isApprox(expected.T_lidar_camera, 1e-12));
  EXPECT_EQ(got.quality.verdict, expected.quality.verdict);
}

TEST(Concurrency, SimulatorFramesFromTwoThreads) {
  const auto& expected = frames();
  sim::SimulatedFrame got[kFrames];
  std::thread first([&] { got[0] = simulator().frame(0); });
  std::thread second([&] { got[1] = simulator().frame(1); });
  first.join();
  second.join();
  for (int i = 0; i < kFrames; ++i) {
    EXPECT_TRUE(got[i].lidar.points == expected[i].lidar.points) << i;
    EXPECT_TRUE(got[i].left.pixels == expected[i].left.pixels) << i;
  }
}

TEST(Concurrency, AtomicWritesOfOneFileNeverShowAHalfFile) {
  test::TempDir dir;
  const std::string path = dir.file("sweep.pcd");
  LidarCloud a, b;
  for (int i = 0; i < 2000; ++i) {
    a.points.emplace_back(i, 1.0, 2.0);
    b.points.emplace_back(-i, 3.0, 4.0);
  }
  io::write_pcd(path, a);
  std::atomic<bool> stop{false};
  std::atomic<int> torn{0};
  std::thread reader([&] {
    while (!stop) {
      const LidarCloud read = io::read_pcd(path);  // throws on a half-written file
      if (read.points != a.points && read.points != b.points) ++torn;
    }
  });
  std::thread writer_a([&] {
    for (int i = 0; i < 20; ++i) io::write_pcd(path, a, io::PcdEncoding::BinaryCompressed);
  });
  std::thread writer_b([&] {
    for (int i = 0; i < 20; ++i) io::write_pcd(path, b, io::PcdEncoding::Ascii);
  });
  writer_a.join();
  writer_b.join();
  stop = true;
  reader.join();
  EXPECT_EQ(torn.load(), 0);
}

}  // namespace
}  // namespace l2s
