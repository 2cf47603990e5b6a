// Which path a simulated sweep takes, over randomised scenes (issue 7: detect
// automatically whether a sweep has scan lines): every spinning lidar, quirks
// on, has rings; every rosette (Avia-, Mid-360-like) sweep is ring-free. A
// rosette sweep of a scene in a small room once measured a ring contrast of
// 2.2 and went down the ring path, where no frame found the board.
#include <l2s/io/ring_recovery.hpp>
#include <l2s/sim/random_scene.hpp>

#include <gtest/gtest.h>

#include <string>

namespace l2s {
namespace {

bool rosette(const std::string& lidar) { return lidar == "avia" || lidar == "mid360"; }

void expect_path(std::uint64_t seed) {
  const sim::RandomScene scene = sim::make_random_scene(seed, 2, 1.0, 1, sim::BoardDraw::Classic);
  const std::string& lidar = scene.simulator->config().lidar;
  for (int i = 0; i < 2; ++i) {
    const io::ScanClassification scan = io::classify_scan(scene.simulator->frame(i).lidar);
    EXPECT_EQ(scan.structure, rosette(lidar) ? io::ScanStructure::RingFree : io::ScanStructure::Rings)
        << "seed " << seed << " (" << scene.summary << "), frame " << i << ": " << scan.reason;
  }
}

TEST(ScanStructureOnRandomScenes, TheRosetteThatLookedLikeRings) { expect_path(1582375095); }

TEST(ScanStructureOnRandomScenes, EverySceneTakesItsLidarsPath) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) expect_path(seed);
}

}  // namespace
}  // namespace l2s
