// Whole datasets: scene files, the DATASET.md layout, ground truth, and
// byte-identical output for the same seed.

#include <l2s/sim/scene_yaml.hpp>
#include <l2s/sim/simulation.hpp>

#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/transform_yaml.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>

namespace l2s::sim {
namespace {

namespace fs = std::filesystem;

/// Every file of a folder with a hash of its bytes, keyed by relative path.
std::map<std::string, std::size_t> hash_tree(const std::string& folder) {
  std::map<std::string, std::size_t> hashes;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file())
      hashes[fs::relative(entry.path(), folder).string()] =
          std::hash<std::string>{}(test::read_bytes(entry.path().string()));
  return hashes;
}

SimulationConfig small_config() {
  SimulationConfig config = SimulationConfig::paper(8, "vlp16");
  config.frames = 2;
  config.seed = 42;
  return config;
}

TEST(SimulateDataset, SameSeedGivesIdenticalBytes) {
  test::TempDir dir;
  SimulationConfig config = small_config();
  simulate_dataset(config, dir.file("a"));
  config.threads = 1;  // the thread count must not matter either
  int calls = 0;
  simulate_dataset(config, dir.file("b"), [&](int done, int total) {
    ++calls;
    EXPECT_EQ(total, 2);
    EXPECT_EQ(done, calls);
  });
  EXPECT_EQ(calls, 2);
  const auto a = hash_tree(dir.file("a"));
  const auto b = hash_tree(dir.file("b"));
  EXPECT_EQ(a, b);
  EXPECT_TRUE(a.count("lidar/000001.pcd") && a.count("left/000000.png") && a.count("right/000001.png") &&
              a.count("ground_truth.yaml") && a.count("scene.yaml") && a.count("left.yaml"));
  // Another seed changes the frames but not the cameras or the truth.
  config.seed = 43;
  simulate_dataset(config, dir.file("c"));
  const auto c = hash_tree(dir.file("c"));
  EXPECT_NE(a.at("lidar/000000.pcd"), c.at("lidar/000000.pcd"));
  EXPECT_NE(a.at("left/000000.png"), c.at("left/000000.png"));
  EXPECT_EQ(a.at("ground_truth.yaml"), c.at("ground_truth.yaml"));
}

TEST(SimulateDataset, FollowsTheDatasetContract) {
  test::TempDir dir;
  SimulationConfig config = small_config();
  config.lidar = "hdl64";
  config.target = Target::paper2017();
  const std::string folder = dir.file("ds");
  simulate_dataset(config, folder);

  const io::Dataset dataset = io::Dataset::open(folder);
  ASSERT_EQ(dataset.size(), 2u);
  EXPECT_NEAR(dataset.cameras().baseline(), 0.12, 1e-9);
  EXPECT_DOUBLE_EQ(dataset.target().board_width, 1.2);
  const auto truth = dataset.ground_truth();
  ASSERT_TRUE(truth.has_value());
  EXPECT_TRUE(truth->matrix().isApprox(paper_setting(8).T_lidar_camera().matrix(), 1e-9));
  const io::Frame frame = dataset.load(0);
  EXPECT_GT(frame.lidar.size(), 50000u);
  EXPECT_EQ(frame.left.width, 1280);
  EXPECT_EQ(frame.right.height, 960);
  // scene.yaml records the transform of the board too.
  EXPECT_NO_THROW(io::read_transform(folder + "/scene.yaml", "T_cambody_board"));

  L2S_NEED_DATASET_CHECKER();
  const std::string command =
      "/usr/bin/python3 " + test::dataset_checker() + " " + folder + " --lidar-beams 64 >/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(SimulateDataset, WritesOneAccumulatedCloudBesideTheImageFrames) {
  test::TempDir dir;
  SimulationConfig config = SimulationConfig::paper(2, "avia");
  config.frames = 3;
  config.accumulated_seconds = 1.0;
  config.accumulated_crop = 0.3;
  const std::string folder = dir.file("acc");
  const DatasetSimulator simulator(config);
  simulator.write(folder);

  const io::Dataset dataset = io::Dataset::open(folder);
  EXPECT_TRUE(dataset.accumulated());
  ASSERT_EQ(dataset.size(), 3u);
  EXPECT_EQ(dataset.lidar_stems(), std::vector<std::string>{"000000"});
  EXPECT_EQ(dataset.lidar_stem(2), "000000");
  const io::Frame frame = dataset.load(0);
  // Ten sweeps' returns, only those within 0.3 m of the board's rectangle.
  const auto truth = simulator.true_hole_centers().lidar;
  const Eigen::Vector3d middle = 0.25 * (truth[0] + truth[1] + truth[2] + truth[3]);
  ASSERT_GT(frame.lidar.size(), 5000u);
  for (const Eigen::Vector3d& p : frame.lidar.points)
    ASSERT_LT((p - middle).norm(), 0.5 * std::hypot(config.target.board_width, config.target.board_height) + 0.6);
  std::size_t whole = 0;
  for (int i = 0; i < 10; ++i) whole += simulator.sweep(i).size();
  EXPECT_LT(frame.lidar.size(), whole);

  L2S_NEED_DATASET_CHECKER();
  const std::string command = "/usr/bin/python3 " + test::dataset_checker() + " " + folder + " >/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(DatasetSimulator, PaperSettingKeepsItsBytes) {
  // Checksums of frame 0 taken at 7cbd45a, before rigs, raw images and looks
  // existed: placement, rendering and noise of a paper setting are unchanged.
  const auto fnv1a = [](const std::vector<std::uint8_t>& bytes) {
    std::uint64_t h = 1469598103934665603ULL;
    for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ULL;
    return h;
  };
  SimulationConfig config = SimulationConfig::paper(5, "hdl32");
  config.frames = 1;
  const DatasetSimulator simulator(config);
  EXPECT_DOUBLE_EQ(simulator.board_pose().x, 3.4);
  EXPECT_DOUBLE_EQ(simulator.board_pose().y, 0.3);
  const SimulatedFrame frame = simulator.frame(0);
  EXPECT_EQ(fnv1a(frame.left.pixels), 0xbeecf2bac321d7b9ULL);
  EXPECT_EQ(fnv1a(frame.right.pixels), 0xfb628813af68c101ULL);
  EXPECT_EQ(simulator.cameras().images, ImageKind::Rectified);
  EXPECT_TRUE(simulator.T_lidar_camera().isApprox(config.setting.T_lidar_camera(), 0.0));
}

TEST(DatasetSimulator, StrictPlacementRefusesABadBoardPose) {
  SimulationConfig config = small_config();
  config.board_pose = BoardPose{12.0, 0.0, 0.0, 0.2, 0.0, 0.0};
  try {
    DatasetSimulator simulator(config);
    FAIL() << "expected l2s::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("hole"), std::string::npos) << e.what();
  }
  config.strict_placement = false;
  config.rig.width = 320;  // keep the render cheap
  config.rig.height = 240;
  const DatasetSimulator simulator(config);
  EXPECT_FALSE(simulator.warnings().empty());
}

TEST(SceneYaml, ReadsEveryKey) {
  const SimulationConfig c = parse_simulation_config(R"(
sensor_pose: {tx: -0.3, ty: 0.2, tz: -0.2, yaw: 0.3, pitch: -0.1, roll: 0.2}
lidar: hdl32
frames: 5
noise_factor: 2.5
seed: 9
target: {board_width: 1.2, board_height: 0.8, hole_spacing_x: 0.3, hole_spacing_y: 0.3}
board_pose: {x: 3.1, y: 0.1, z: -0.2, yaw: 0.25, pitch: 0.05, roll: 0.04}
camera: {width: 640, height: 480, horizontal_fov: 0.8, baseline: 0.2}
scene:
  camera_height: 1.6
  wall_gap: 2.5
  default_clutter: false
  clutter:
    - {center: [5.0, -2.5, -1.0], size: [1.0, 1.0, 1.0], yaw: 0.3}
strict_placement: false
threads: 1
)");
  EXPECT_EQ(c.setting_index, 0);
  EXPECT_DOUBLE_EQ(c.setting.pitch, -0.1);
  EXPECT_EQ(c.lidar, "hdl32");
  EXPECT_EQ(c.frames, 5);
  EXPECT_DOUBLE_EQ(c.noise_factor, 2.5);
  EXPECT_EQ(c.seed, 9u);
  EXPECT_DOUBLE_EQ(c.target.board_height, 0.8);
  ASSERT_TRUE(c.board_pose.has_value());
  EXPECT_DOUBLE_EQ(c.board_pose->yaw, 0.25);
  EXPECT_EQ(c.rig.width, 640);
  EXPECT_DOUBLE_EQ(c.rig.baseline, 0.2);
  EXPECT_DOUBLE_EQ(c.layout.camera_height, 1.6);
  EXPECT_FALSE(c.layout.default_clutter);
  ASSERT_EQ(c.layout.extra_clutter.size(), 1u);
  EXPECT_DOUBLE_EQ(c.layout.extra_clutter[0].half_size.x(), 0.5);
  EXPECT_FALSE(c.strict_placement);

  const SimulationConfig preset = parse_simulation_config("setting: 9\ntarget: paper2017\n");
  EXPECT_EQ(preset.setting_index, 9);
  EXPECT_DOUBLE_EQ(preset.setting.tz, 1.108);
  EXPECT_DOUBLE_EQ(preset.target.hole_spacing_x, 0.3);
}

TEST(SceneYaml, RejectsBadInputNamingTheKey) {
  const auto message = [](const std::string& text) {
    try {
      parse_simulation_config(text, "scene.yaml");
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("framez: 3").find("framez"), std::string::npos);
  EXPECT_NE(message("setting: 12").find("setting"), std::string::npos);
  EXPECT_NE(message("lidar: hdl16").find("lidar"), std::string::npos);
  EXPECT_NE(message("frames: many").find("frames"), std::string::npos);
  EXPECT_NE(message("setting: 1\nsensor_pose: {tx: 0}").find("either"), std::string::npos);
  EXPECT_NE(message("target: {hole_radius: 0.4}").find("hole"), std::string::npos);
  EXPECT_NE(message("scene: {clutter: [{center: [1, 2]}]}").find("clutter"), std::string::npos);
  EXPECT_THROW(load_simulation_config("/nonexistent/scene.yaml"), FileError);
}

}  // namespace
}  // namespace l2s::sim
