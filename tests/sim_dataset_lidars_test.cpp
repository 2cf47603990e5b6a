// Datasets of the lidars of real recordings: a ring-free lidar writes
// `x y z intensity` only and passes the dataset checker; quirks and scene
// elements are read from scene files and recorded in scene.yaml.

#include <l2s/sim/scene_yaml.hpp>
#include <l2s/sim/simulation.hpp>

#include <l2s/error.hpp>
#include <l2s/io/pcd.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <filesystem>

namespace l2s::sim {
namespace {

namespace fs = std::filesystem;

SimulationConfig small(const std::string& lidar, int setting) {
  SimulationConfig config = SimulationConfig::paper(setting, lidar);
  config.frames = 2;
  config.seed = 5;
  config.rig.width = 640;  // keep the render cheap
  config.rig.height = 480;
  config.rig.horizontal_fov = 0.7505;
  return config;
}

/// The PCD header's FIELDS line.
std::string pcd_fields(const std::string& path) {
  const std::string bytes = test::read_bytes(path);
  const std::size_t at = bytes.find("FIELDS");
  return bytes.substr(at, bytes.find('\n', at) - at);
}

TEST(RingFreeDataset, WritesNoRingAndPassesTheChecker) {
  test::TempDir dir;
  const std::string folder = dir.file("avia");
  simulate_dataset(small("avia", 1), folder);
  EXPECT_EQ(pcd_fields(folder + "/lidar/000001.pcd"), "FIELDS x y z intensity");
  const LidarCloud cloud = io::read_pcd(folder + "/lidar/000000.pcd");
  EXPECT_FALSE(cloud.has_ring());
  EXPECT_GT(cloud.size(), 10000u);
  L2S_NEED_DATASET_CHECKER();
  const std::string script = test::dataset_checker();
  const std::string command = "/usr/bin/python3 " + script + " " + folder + " > " + dir.file("check.log") + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << test::read_bytes(dir.file("check.log"));
}

TEST(QuirkyDataset, RecordsTheQuirksAndTheLaserTable) {
  test::TempDir dir;
  SimulationConfig config = small("vlp16", 8);
  config.lidar_quirks = LidarQuirks::all(7);
  config.layout.board_stand = true;
  config.layout.side_wall_distance = 2.5;
  const DatasetSimulator simulator(config);
  EXPECT_EQ(simulator.lidar_model().corrections.size(), 16u);
  simulator.write(dir.file("ds"));
  const YAML::Node scene = YAML::LoadFile(dir.file("ds/scene.yaml"));
  EXPECT_TRUE(scene["lidar_quirks"]["laser_table"].as<bool>());
  EXPECT_TRUE(scene["lidar_quirks"]["beam_footprint"].as<bool>());
  EXPECT_EQ(scene["lidar_quirks"]["return_mode"].as<std::string>(), "strongest");
  EXPECT_EQ(scene["lidar_quirks"]["table_seed"].as<int>(), 7);
  ASSERT_EQ(scene["laser_table"].size(), 16u);
  EXPECT_NEAR(scene["laser_table"][3][2].as<double>(), simulator.lidar_model().corrections[3].vertical_offset, 1e-9);
  EXPECT_TRUE(scene["scene"]["board_stand"].as<bool>());
  EXPECT_DOUBLE_EQ(scene["scene"]["side_wall_distance"].as<double>(), 2.5);
  // The same config, any thread count: the same sweep.
  config.threads = 1;
  config.board_pose = simulator.board_pose();  // skip the search
  const DatasetSimulator again(config);
  const LidarCloud a = simulator.sweep(1), b = again.sweep(1);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]);
}

TEST(SceneYaml, ReadsLidarQuirksAndSceneElements) {
  const SimulationConfig c = parse_simulation_config(R"(
lidar: mid360
lidar_quirks: {laser_table: false, beam_footprint: true, return_mode: last, table_seed: 12}
scene:
  board_stand: true
  side_wall_distance: 1.5
  near_clutter: 2
  pillar: true
)");
  EXPECT_EQ(c.lidar, "mid360");
  EXPECT_FALSE(c.lidar_quirks.laser_table);
  EXPECT_TRUE(c.lidar_quirks.beam_footprint);
  EXPECT_EQ(c.lidar_quirks.return_mode, ReturnMode::Last);
  EXPECT_EQ(c.lidar_quirks.table_seed, 12u);
  EXPECT_TRUE(c.layout.board_stand);
  EXPECT_DOUBLE_EQ(c.layout.side_wall_distance, 1.5);
  EXPECT_EQ(c.layout.near_clutter, 2);
  EXPECT_TRUE(c.layout.pillar);
  const SimulationConfig all = parse_simulation_config("lidar_quirks: true\n");
  EXPECT_TRUE(all.lidar_quirks.laser_table && all.lidar_quirks.beam_footprint);
  EXPECT_FALSE(parse_simulation_config("lidar_quirks: false\n").lidar_quirks.any());
  EXPECT_FALSE(parse_simulation_config("").lidar_quirks.any());  // off by default
}

TEST(SceneYaml, RejectsBadQuirksAndElementsNamingTheKey) {
  const auto message = [](const std::string& text) {
    try {
      parse_simulation_config(text, "scene.yaml");
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("lidar_quirks: {return_mode: loudest}\n").find("lidar_quirks.return_mode"), std::string::npos);
  EXPECT_NE(message("lidar_quirks: {footprint: true}\n").find("lidar_quirks.footprint"), std::string::npos);
  EXPECT_NE(message("lidar_quirks: maybe\n").find("lidar_quirks"), std::string::npos);
  EXPECT_NE(message("scene: {side_wall_distance: 0.2}\n").find("scene.side_wall_distance"), std::string::npos);
  EXPECT_NE(message("lidar: ouster\n").find("lidar"), std::string::npos);
}

}  // namespace
}  // namespace l2s::sim
