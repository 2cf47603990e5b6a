// The lidar-lidar simulator: where it puts lidar2, what it writes (the
// dataset contract, read back by Dataset), and a lidar2 that cannot see.
#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/sim/lidar_pair.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace l2s::sim {
namespace {

LidarPairConfig config(int poses, int frames, std::uint64_t seed, const std::string& lidar2 = "hdl32") {
  LidarPairConfig c;
  c.base = SimulationConfig::paper(1, "vlp16");
  c.base.frames = frames;
  c.base.seed = seed;
  c.base.threads = 2;
  c.lidar2 = lidar2;
  c.poses = poses;
  return c;
}

TEST(LidarPairSimulator, Lidar2StandsNearTheFirstAtASeededPose) {
  const LidarPairSimulator a(config(1, 1, 5)), again(config(1, 1, 5)), other(config(1, 1, 6));
  const Eigen::Isometry3d T = a.T_lidar_lidar2();
  EXPECT_GE(T.translation().norm(), 0.3);
  EXPECT_LE(T.translation().norm(), 1.0 + 1e-9);
  const double angle = Eigen::AngleAxisd(T.rotation()).angle() * 180.0 / M_PI;
  EXPECT_GT(angle, 0.0);
  EXPECT_LE(angle, 21.0);
  EXPECT_TRUE(T.isApprox(again.T_lidar_lidar2(), 0.0));
  EXPECT_FALSE(T.isApprox(other.T_lidar_lidar2(), 1e-6));
  const SimulatedFrame frame = a.frame(0);
  EXPECT_GT(frame.lidar.size(), 1000u);
  EXPECT_GT(frame.lidar2.size(), frame.lidar.size());  // 32 lasers against 16
  EXPECT_TRUE(frame.left.empty());
}

TEST(LidarPairSimulator, PosesWithMovingFramesBetween) {
  const LidarPairSimulator simulator(config(3, 2, 1));
  EXPECT_EQ(simulator.poses().size(), 3u);
  EXPECT_EQ(simulator.moving_frames(), (std::vector<int>{2, 3, 6, 7}));
  EXPECT_EQ(simulator.frames(), 3 * 2 + 4);
  EXPECT_TRUE(simulator.warnings().empty());
}

TEST(LidarPairSimulator, WritesADatasetThatPassesTheContract) {
  test::TempDir dir;
  const std::string folder = dir.file("pair");
  const LidarPairSimulator simulator(config(1, 2, 1, "mid360"));
  simulator.write(folder);
  const io::Dataset dataset = io::Dataset::open(folder);
  EXPECT_TRUE(dataset.has_lidar2());
  EXPECT_EQ(static_cast<int>(dataset.size()), simulator.frames());
  ASSERT_TRUE(dataset.ground_truth());
  EXPECT_POSE_NEAR(*dataset.ground_truth(), simulator.T_lidar_lidar2(), 1e-9, 1e-12);
  const io::Frame frame = dataset.load(0);
  EXPECT_TRUE(frame.lidar.has_ring());
  EXPECT_FALSE(frame.lidar2.has_ring());  // Mid-360: ring-free, left for accumulation
  EXPECT_GT(frame.lidar2.size(), 1000u);

  L2S_NEED_DATASET_CHECKER();
  const std::string command = "/usr/bin/python3 " + test::dataset_checker() + " " + folder + " --lidar-beams 16 > " +
                              dir.file("check.log") + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << test::read_bytes(dir.file("check.log"));
}

TEST(LidarPairSimulator, Lidar2ThatCannotSeeTheBoardIsAnError) {
  LidarPairConfig c = config(1, 1, 1, "avia");
  c.lidar2_setting = SensorSetting{0.0, 0.0, 0.0, M_PI, 0.0, 0.0};  // looking backwards
  // A small grid: a search in which nothing passes tries every pose of it.
  PlacementSearch grid;
  grid.distances = {3.2};
  grid.lateral = {-0.15};
  grid.heights = {-0.1};  // the first lidar's pose of setting 1
  c.base.placement_search = grid;
  EXPECT_THROW(LidarPairSimulator{c}, Error);
  c.base.strict_placement = false;  // lenient: a warning instead
  const LidarPairSimulator lenient(c);
  ASSERT_EQ(lenient.warnings().size(), 1u);
  EXPECT_NE(lenient.warnings()[0].find("lidar2"), std::string::npos);
}

}  // namespace
}  // namespace l2s::sim
