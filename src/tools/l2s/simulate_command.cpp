// l2s simulate: writes a synthetic dataset with exact ground truth (the
// paper's test suite). Options given on the command line override a scene file.

#include "commands.hpp"
#include "progress_bar.hpp"

#include <l2s/error.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/sim/lidar_pair.hpp>
#include <l2s/sim/multi_pose.hpp>
#include <l2s/sim/random_scene.hpp>
#include <l2s/sim/scene_yaml.hpp>
#include <l2s/sim/simulation.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

struct SimulateOptions {
  std::string out_dir;
  std::string scene_file;
  std::optional<std::uint64_t> random_scene;  // a randomised scene of the `scenes` experiment
  std::string scene_boards = "all";           // ... drawing the boards of `l2s suite --scene-boards`
  std::string target_file;
  std::string board = "default";
  std::string lidar = "vlp16";
  int setting = 1;
  int frames = 30;
  double noise = 1.0;
  std::uint64_t seed = 1;
  int threads = 0;
  bool lenient = false;
  bool overwrite = false;
  bool mono = false;     // the left camera alone: a lidar-mono dataset
  bool markers = false;  // the default markers on the board (mono: implied when the board has none)

  // --- Camera side: the rig and the scene's look (override a scene file) ---
  int width = 1280;
  int height = 960;
  double hfov_deg = 43.0;
  double baseline = 0.12;
  double roll_deg = 0.0;
  std::string distortion = "none";
  std::string board_texture = "matte";
  std::string background = "textured";
  bool shadows = false;

  // --- Lidar side ---
  bool lidar_quirks = false;
  double accumulate = 0.0;  // [s] > 0: one accumulated cloud beside the image frames (`lidar: accumulated`)
  double crop = 0.0;        // [m] with accumulate: keep the returns this close to the board

  // --- Several board poses (issue 9) ---
  std::optional<int> poses;  // absent: one pose, the single-pose dataset as always
  int moving_frames = 2;

  // --- Lidar to lidar (issue 9) ---
  std::string lidar2;  // a second lidar model: a lidar-lidar dataset, no images
};

/// Applies the rig and look options that were given on the command line.
void apply_camera_options(const SimulateOptions& options, const CLI::App& command,
                          sim::SimulationConfig* config) {
  const auto given = [&](const char* name) { return command.count(name) > 0; };
  sim::StereoRig& rig = config->rig;
  if (given("--width")) rig.width = options.width;
  if (given("--height")) rig.height = options.height;
  if (given("--hfov")) rig.horizontal_fov = options.hfov_deg * 3.141592653589793 / 180.0;
  if (given("--baseline")) rig.baseline = options.baseline;
  if (given("--roll")) rig.roll = options.roll_deg * 3.141592653589793 / 180.0;
  // After size and field of view: the typical lenses depend on both.
  if (given("--distortion"))
    rig = rig.with_real_lenses(sim::distortion_model_from_name(options.distortion, "--distortion"));
  sim::Appearance& look = config->appearance;
  if (given("--board-texture")) look.board = sim::board_texture_from_name(options.board_texture, "--board-texture");
  if (given("--background")) look.background = sim::background_from_name(options.background, "--background");
  if (options.shadows) look.shadows = true;
}

void add_camera_options(CLI::App* command, SimulateOptions* options) {
  command->add_option("--width", options->width, "image width [px]")->check(CLI::Range(16, 16384));
  command->add_option("--height", options->height, "image height [px]")->check(CLI::Range(16, 16384));
  command->add_option("--hfov", options->hfov_deg, "horizontal field of view [deg]")
      ->check(CLI::Range(3.0, 170.0));
  command->add_option("--baseline", options->baseline, "stereo baseline [m]")->check(CLI::Range(0.01, 5.0));
  command->add_option("--roll", options->roll_deg,
                      "the rig turned about its optical axis [deg] (90: on its side, 180: upside down)")
      ->check(CLI::Range(-360.0, 360.0));
  command->add_option("--distortion", options->distortion,
                      "lenses of a real pair with this distortion, raw images (none: rectified)")
      ->check(CLI::IsMember({"none", "plumb_bob", "equidistant"}));
  command->add_option("--board-texture", options->board_texture, "board look")
      ->check(CLI::IsMember(sim::board_texture_names()));
  command->add_option("--background", options->background, "wall look")
      ->check(CLI::IsMember(sim::background_names()));
  command->add_flag("--shadows", options->shadows, "hard shadows from the sun");
}

// A folder that already holds frames is only replaced on request, and then
// wholly: leftover frames of a longer earlier run would corrupt the dataset.
void prepare_output(const std::string& folder, bool overwrite) {
  if (!fs::exists(folder)) return;
  if (!fs::is_directory(folder)) throw FileError(folder, "exists and is not a folder");
  if (fs::is_empty(folder)) return;
  if (!overwrite) throw FileError(folder, "folder is not empty (use --overwrite to replace the dataset)");
  for (const char* sub : {"lidar", "left", "right", "lidar2"}) fs::remove_all(fs::path(folder) / sub);
  for (const char* file : {"dataset.yaml", "left.yaml", "right.yaml", "target.yaml", "ground_truth.yaml", "scene.yaml",
                           "poses.yaml", "lidar2.yaml"})
    fs::remove(fs::path(folder) / file);
}

/// Writes the simulator's dataset and prints what it wrote.
int write_dataset(const sim::DatasetSimulator& simulator, const SimulateOptions& options) {
  const sim::SimulationConfig& config = simulator.config();
  prepare_output(options.out_dir, options.overwrite);
  for (const auto& warning : simulator.warnings()) std::cerr << "l2s: warning: " << warning << "\n";
  ProgressBar progress("simulate", static_cast<std::size_t>(config.frames));
  simulator.write(options.out_dir, [&](int done, int) { progress.update(done); });
  progress.finish();
  const Eigen::Vector3d t = simulator.T_lidar_camera().translation();
  std::printf("wrote %s: %d frames, %s%s, setting %d, K = %g, seed %llu\n", options.out_dir.c_str(),
              config.frames, config.lidar.c_str(), config.lidar_quirks.any() ? " with quirks" : "",
              config.setting_index, config.noise_factor, static_cast<unsigned long long>(config.seed));
  if (config.accumulated_seconds > 0.0)
    std::printf("lidar: accumulated: one cloud of %g s of returns beside the %d image frames%s\n",
                config.accumulated_seconds, config.frames,
                config.accumulated_crop > 0.0 ? (", cropped to " + std::to_string(config.accumulated_crop).substr(0, 4) +
                                                 " m around the board").c_str()
                                              : "");
  std::printf("ground truth T_lidar_camera translation (%.4f, %.4f, %.4f) m\n", t.x(), t.y(), t.z());
  std::printf("%s %dx%d, %s images\n", config.mono ? "mono camera" : "cameras", config.rig.width, config.rig.height,
              config.rig.images() == ImageKind::Raw ? "raw" : "rectified");
  return 0;
}

/// Writes a multi-pose dataset (--poses) and prints its poses and moving frames.
int write_multi_pose(const sim::SimulationConfig& config, const SimulateOptions& options) {
  sim::MultiPoseConfig multi;
  multi.base = config;
  multi.poses = *options.poses;
  multi.moving_frames = options.moving_frames;
  const sim::MultiPoseSimulator simulator(multi);
  prepare_output(options.out_dir, options.overwrite);
  for (const auto& warning : simulator.warnings()) std::cerr << "l2s: warning: " << warning << "\n";
  ProgressBar progress("simulate", static_cast<std::size_t>(simulator.frames()));
  simulator.write(options.out_dir, [&](int done, int) { progress.update(done); });
  progress.finish();
  std::printf("wrote %s: %d frames, %zu board poses of %d frames, %zu moving frames, %s, setting %d, K = %g, seed %llu\n",
              options.out_dir.c_str(), simulator.frames(), simulator.poses().size(), config.frames,
              simulator.moving_frames().size(), config.lidar.c_str(), config.setting_index, config.noise_factor,
              static_cast<unsigned long long>(config.seed));
  for (const sim::PoseSegment& s : simulator.segments())
    if (s.pose_index >= 0)
      std::printf("  pose %d: frames %d-%d, board at x %.2f y %.2f z %.2f m, yaw %.0f pitch %.0f deg\n", s.pose_index,
                  s.first_frame, s.first_frame + s.frames - 1, s.pose.x, s.pose.y, s.pose.z, s.pose.yaw * 180 / M_PI,
                  s.pose.pitch * 180 / M_PI);
  return 0;
}

/// Writes a lidar-lidar dataset (--lidar2) and prints where lidar2 stands.
int write_lidar_pair(const sim::SimulationConfig& config, const SimulateOptions& options) {
  sim::LidarPairConfig pair;
  pair.base = config;
  pair.lidar2 = options.lidar2;
  pair.poses = options.poses.value_or(1);
  pair.moving_frames = options.moving_frames;
  const sim::LidarPairSimulator simulator(pair);
  prepare_output(options.out_dir, options.overwrite);
  for (const auto& warning : simulator.warnings()) std::cerr << "l2s: warning: " << warning << "\n";
  ProgressBar progress("simulate", static_cast<std::size_t>(simulator.frames()));
  simulator.write(options.out_dir, [&](int done, int) { progress.update(done); });
  progress.finish();
  std::printf("wrote %s: lidar-lidar, %d frames, %zu board poses of %d frames, %zu moving frames, %s -> %s, K = %g, "
              "seed %llu\n",
              options.out_dir.c_str(), simulator.frames(), simulator.poses().size(), config.frames,
              simulator.moving_frames().size(), config.lidar.c_str(), options.lidar2.c_str(), config.noise_factor,
              static_cast<unsigned long long>(config.seed));
  const Eigen::Isometry3d T = simulator.T_lidar_lidar2();
  const Eigen::Vector3d t = T.translation();
  std::printf("ground truth T_lidar_lidar2 translation (%.4f, %.4f, %.4f) m, rotation %.2f deg\n", t.x(), t.y(),
              t.z(), Eigen::AngleAxisd(T.rotation()).angle() * 180.0 / M_PI);
  return 0;
}

int run_simulate(const SimulateOptions& options, const CLI::App& command) {
  const auto given = [&](const char* name) { return command.count(name) > 0; };
  if (options.random_scene) {
    const sim::BoardDraw boards = options.scene_boards == "classic"  ? sim::BoardDraw::Classic
                                  : options.scene_boards == "marked" ? sim::BoardDraw::Marked
                                                                     : sim::BoardDraw::All;
    const sim::RandomScene scene = sim::make_random_scene(*options.random_scene, options.frames, options.noise,
                                                          options.threads, boards);
    std::printf("random scene %llu (%d redraws): %s\n", static_cast<unsigned long long>(scene.seed), scene.redraws,
                scene.summary.c_str());
    if (options.accumulate > 0.0) {  // the same scene, its lidar kept as one cloud
      sim::SimulationConfig config = scene.simulator->config();
      config.accumulated_seconds = options.accumulate;
      config.accumulated_crop = options.crop;
      config.board_pose = scene.simulator->board_pose();
      return write_dataset(sim::DatasetSimulator(config), options);
    }
    return write_dataset(*scene.simulator, options);
  }
  sim::SimulationConfig config = options.scene_file.empty()
                                     ? sim::SimulationConfig::paper(options.setting, options.lidar)
                                     : sim::load_simulation_config(options.scene_file);
  if (!options.scene_file.empty() && given("--setting")) {
    config.setting = sim::paper_setting(options.setting);
    config.setting_index = options.setting;
  }
  if (!options.scene_file.empty() && given("--lidar")) config.lidar = options.lidar;
  if (options.scene_file.empty() || given("--frames")) config.frames = options.frames;
  if (options.scene_file.empty() || given("--noise")) config.noise_factor = options.noise;
  if (options.scene_file.empty() || given("--seed")) config.seed = options.seed;
  if (options.scene_file.empty() || given("--board")) config.target = Target::preset(options.board);
  if (!options.target_file.empty()) config.target = io::read_target(options.target_file);
  // A mono camera needs markers; a board without them gets the default ones.
  if ((options.markers || options.mono) && !config.target.markers)
    config.target.markers = MarkerLayout::corners_default();
  if (options.mono) config.mono = true;
  if (given("--threads")) config.threads = options.threads;
  if (options.lenient) config.strict_placement = false;
  config.accumulated_seconds = options.accumulate;
  config.accumulated_crop = options.crop;
  apply_camera_options(options, command, &config);
  if (options.lidar_quirks) config.lidar_quirks = sim::LidarQuirks::all(config.lidar_quirks.table_seed);

  if (!options.lidar2.empty()) return write_lidar_pair(config, options);
  if (options.poses) return write_multi_pose(config, options);
  return write_dataset(sim::DatasetSimulator(config), options);
}

}  // namespace

void add_simulate_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand("simulate", "Write a synthetic dataset with exact ground truth");
  auto options = std::make_shared<SimulateOptions>();
  command->add_option("out_dir", options->out_dir, "output dataset folder")->required();
  command->add_option("--setting", options->setting, "Table I setting of the paper")
      ->check(CLI::Range(1, 9));
  command->add_option("--lidar", options->lidar, "lidar model (avia, mid360: ring-free rosette scans)")
      ->check(CLI::IsMember(sim::LidarModel::names()));
  command->add_option("--frames", options->frames, "number of frames")->check(CLI::Range(1, 100000));
  command->add_option("--noise", options->noise, "noise factor K (sigma = K * 8 mm, K * 0.007)")
      ->check(CLI::Range(0.0, 100.0));
  command->add_option("--seed", options->seed, "random seed (same seed, same bytes)");
  command->add_option("--board", options->board, "board preset")
      ->check(CLI::IsMember({"default", "markers", "paper2017"}));
  command->add_option("--target", options->target_file, "board geometry from a target.yaml")
      ->check(CLI::ExistingFile);
  command->add_option("--scene", options->scene_file, "scene file: custom pose, board, placement")
      ->check(CLI::ExistingFile);
  command->add_option("--random-scene", options->random_scene,
                      "a randomised scene of the suite's `scenes` experiment (any rig, look, lidar and quirks; "
                      "--frames, --noise, --threads apply)")
      ->excludes("--scene");
  command->add_option("--scene-boards", options->scene_boards,
                      "the boards --random-scene draws, as `l2s suite --scene-boards`: all, classic or marked")
      ->check(CLI::IsMember({"all", "classic", "marked"}))
      ->needs("--random-scene")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "worker threads (0 = all cores)");
  command->add_flag("--lenient", options->lenient, "warn instead of failing when the placement check fails");
  command->add_flag("--overwrite", options->overwrite, "replace an existing dataset in out_dir");
  command->add_flag("--mono", options->mono,
                    "a lidar-mono dataset: the left camera alone; the board gets the default ArUco markers "
                    "unless its target.yaml has markers");
  command->add_flag("--markers", options->markers,
                    "print the default ArUco markers (four 0.2 m DICT_6X6_250 near the corners) on the board");
  add_camera_options(command, options.get());
  command->add_option("--poses", options->poses,
                      "board poses spread over the shared view, --frames each, with moving frames between (1..5)")
      ->check(CLI::Range(1, 5))
      ->excludes("--random-scene");
  command->add_option("--moving-frames", options->moving_frames,
                      "with --poses: frames between two poses with the board on its way (default 2)")
      ->check(CLI::Range(0, 10));
  command->add_option("--lidar2", options->lidar2,
                      "a second lidar model: writes a lidar-lidar dataset (lidar/, lidar2/, no images) with "
                      "lidar2 at a seeded random pose near the first; works with --poses")
      ->check(CLI::IsMember(sim::LidarModel::names()))
      ->excludes("--random-scene");
  command->add_flag("--lidar-quirks", options->lidar_quirks,
                    "simulate a real lidar: per-laser calibration table, beam divergence and mixed returns");
  command->add_option("--accumulate", options->accumulate,
                      "seconds of lidar returns (10 sweeps/s) kept as one cloud beside the --frames image frames: "
                      "a `lidar: accumulated` dataset, as solid-state lidar users keep a static board")
      ->check(CLI::Range(0.1, 60.0))
      ->excludes("--poses")
      ->excludes("--lidar2");
  command->add_option("--crop", options->crop,
                      "with --accumulate: keep only the returns within this many metres of the board")
      ->check(CLI::Range(0.0, 100.0))
      ->needs("--accumulate");
  command->callback([&runner, options, command] {
    runner = [options, command] { return run_simulate(*options, *command); };
  });
}

}  // namespace l2s::cli
