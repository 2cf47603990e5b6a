#pragma once
// Each sub-command of `l2s` registers its options on the CLI11 app and sets the
// function that runs it; main() parses, runs and maps errors to exit codes.
// CLI11 is declared here, not included: its header alone costs 8 s of compile
// per source (measured, -O3), and only the commands' sources use it.

#include <l2s/calibrator.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/recording/frame_pairing.hpp>

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace l2s::cli {

/// Runs a parsed sub-command; returns the process exit code.
using Runner = std::function<int()>;

void add_calibrate_command(CLI::App& app, Runner& runner);
void add_info_command(CLI::App& app, Runner& runner);
void add_params_command(CLI::App& app, Runner& runner);
void add_evaluate_command(CLI::App& app, Runner& runner);
void add_simulate_command(CLI::App& app, Runner& runner);
void add_suite_command(CLI::App& app, Runner& runner);
void add_detect_command(CLI::App& app, Runner& runner);
void add_check_command(CLI::App& app, Runner& runner);
void add_extract_command(CLI::App& app, Runner& runner);

/// Prints the topics a recording is read from (and whether its images are raw).
void print_recording_topics(const RecordingTopics& topics, bool raw_images);
/// The options that choose a recording's topics and pair its messages
/// (`--lidar-topic`, ..., `--tolerance`); `lidar2`: with --lidar2-topic.
void add_recording_options(CLI::App* command, RecordingTopics& topics, PairingParams& pairing, bool lidar2);

struct CalibrateOptions;
/// `l2s calibrate RECORDING` on a ROS 1 bag (calibrate_recording.cpp); the exit code.
int calibrate_recording(const CalibrateOptions& options);

/// What `l2s calibrate` passes on for a lidar-lidar dataset.
struct LidarPairRun {
  Calibrator::Params params;  ///< its lidar side serves both lidars
  std::string preset;         ///< preset name or params file, for the result file
  std::string output;         ///< result YAML; empty: DATASET/calibration.yaml
  int frames = 0;             ///< use only the first N frames (0: all)
  bool verbose = false;       ///< print why each frame was not used
};
/// What a lidar-lidar calibration reads: its frames (the two sweeps of
/// each, rings settled as io::Dataset loads them), board and truth.
struct LidarPairInput {
  std::string source;          ///< the dataset folder or recording, for the result file
  std::string default_output;  ///< the result YAML when -o does not say
  Target target;
  std::optional<Eigen::Isometry3d> truth;
  std::size_t frames = 0;      ///< frames available
  /// Calls `visit` with each of the first `count` frames in order.
  std::function<void(std::size_t count, const std::function<void(const io::Frame&)>& visit)> read_frames;
};
/// `l2s calibrate` on a lidar-lidar dataset or recording (calibrate_lidar_pair.cpp); the exit code.
int calibrate_lidar_pair(const LidarPairInput& input, const LidarPairRun& run);

// Inputs several sub-commands share (command_inputs.cpp).
/// Whether `path` is a file that starts as a ROS bag does (recording_info.cpp).
bool is_ros1_bag(const std::string& path);
/// `l2s info RECORDING` on a ROS 1 bag; the exit code.
int print_recording_info(const std::string& path);

/// Opens a dataset and prints its warnings to stderr.
io::Dataset open_dataset_warning(const std::string& folder);
/// The params of --params FILE when given, else of --preset NAME.
Calibrator::Params params_from(const std::string& preset, const std::string& params_file);
/// The lidar path of a frame's sweep and why, as the calibrator takes it
/// with `params` (l2s::lidar_path). The reader has already dropped a ring
/// field that does not give the scan lines and recovered the rings from the
/// returns; the words say so.
std::string frame_path(const io::Frame& frame, const Calibrator::Params& params);

}  // namespace l2s::cli
