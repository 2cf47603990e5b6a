// The random draw of a scene's lidar side: deterministic per seed, within the
// documented ranges, and it composes into a dataset simulator.

#include <l2s/sim/lidar_scene_draw.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>

namespace l2s::sim {
namespace {

TEST(LidarSceneDraw, SameSeedSameScene) {
  std::mt19937_64 a(17), b(17), c(18);
  const LidarSceneDraw x = draw_lidar_scene(a), y = draw_lidar_scene(b), z = draw_lidar_scene(c);
  EXPECT_EQ(x.lidar, y.lidar);
  EXPECT_EQ(x.quirks.table_seed, y.quirks.table_seed);
  EXPECT_EQ(x.lidar_pose.tx, y.lidar_pose.tx);
  EXPECT_EQ(x.lidar_pose.roll, y.lidar_pose.roll);
  EXPECT_EQ(x.layout.side_wall_distance, y.layout.side_wall_distance);
  EXPECT_EQ(x.board_yaw, y.board_yaw);
  EXPECT_NE(x.lidar_pose.tx, z.lidar_pose.tx);
}

TEST(LidarSceneDraw, StaysWithinTheDocumentedRanges) {
  std::mt19937_64 rng(3);
  std::set<std::string> models;
  std::set<ReturnMode> modes;
  int stands = 0, corridors = 0;
  for (int i = 0; i < 300; ++i) {
    const LidarSceneDraw d = draw_lidar_scene(rng);
    models.insert(d.lidar);
    modes.insert(d.quirks.return_mode);
    EXPECT_TRUE(d.quirks.laser_table && d.quirks.beam_footprint);
    const SensorSetting& p = d.lidar_pose;
    EXPECT_LE(std::sqrt(p.tx * p.tx + p.ty * p.ty + p.tz * p.tz), 1.0);
    EXPECT_GE(p.tz, -0.9);
    EXPECT_LE(std::abs(p.yaw), 0.7);
    EXPECT_LE(std::abs(p.pitch), 0.3);
    EXPECT_LE(std::abs(p.roll), 0.3);
    EXPECT_GE(d.board_distance, 1.5);
    EXPECT_LE(d.board_distance, d.lidar == "vlp16" ? 3.5 : 6.0);
    EXPECT_GE(std::abs(d.board_yaw), 0.1);
    EXPECT_LE(std::abs(d.board_yaw), 0.5);
    EXPECT_LE(std::abs(d.board_pitch), 0.1);
    EXPECT_LE(std::abs(d.board_roll), 0.1);
    EXPECT_NO_THROW(d.layout.validate());
    if (d.layout.side_wall_distance > 0.0) {
      ++corridors;
      EXPECT_GE(d.layout.side_wall_distance, std::abs(p.ty) + 0.5 - 1e-12);
      EXPECT_LE(d.layout.side_wall_distance, 3.0);
    }
    EXPECT_LE(d.layout.near_clutter, 3);
    stands += d.layout.board_stand;
  }
  EXPECT_EQ(models.size(), 5u);
  EXPECT_EQ(modes.size(), 3u);
  EXPECT_NEAR(stands / 300.0, 0.7, 0.1);
  EXPECT_NEAR(corridors / 300.0, 0.5, 0.1);
}

TEST(LidarSceneDraw, ComposesIntoADatasetSimulator) {
  // The first draw of this seed that a wide camera can place (most can).
  std::mt19937_64 rng(11);
  SimulationConfig config;
  config.rig.width = 640;
  config.rig.height = 480;
  config.rig.horizontal_fov = 1.2;
  config.frames = 1;
  for (int attempt = 0; attempt < 10; ++attempt) {
    const LidarSceneDraw draw = draw_lidar_scene(rng);
    draw.apply_to(&config);
    EXPECT_EQ(config.setting_index, 0);
    EXPECT_EQ(config.rig.width, 640);  // the camera side is left alone
    std::unique_ptr<DatasetSimulator> built;
    try {
      built = std::make_unique<DatasetSimulator>(config);
    } catch (const Error&) {
      continue;  // no pose fits this draw: the experiment redraws
    }
    const DatasetSimulator& simulator = *built;
    EXPECT_NEAR(simulator.board_pose().x, draw.board_distance, 1e-12);
    EXPECT_NEAR(simulator.board_pose().yaw, draw.board_yaw, 1e-12);
    const LidarCloud cloud = simulator.sweep(0);
    EXPECT_GT(cloud.size(), 1000u);
    EXPECT_EQ(cloud.has_ring(), simulator.lidar_model().has_rings());
    return;
  }
  FAIL() << "no draw of 10 could be placed";
}

}  // namespace
}  // namespace l2s::sim
