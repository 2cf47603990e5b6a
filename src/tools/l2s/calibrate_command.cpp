// l2s calibrate DATASET|RECORDING: streams a dataset folder (or a ROS 1
// recording's paired frames, calibrate_recording.cpp) through the
// Calibrator, writes the result (atomically) and an overlay image, prints a
// short report with the verdict of the scene check. A failed check exits
// non-zero and writes no result (unless --keep-failed); a suspect one warns
// loudly.

#include "calibrate_options.hpp"
#include "calibration_report.hpp"
#include "commands.hpp"
#include "frame_feed.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

int calibrate_dataset(const CalibrateOptions& options) {
  const auto dataset = open_dataset_warning(options.input);
  const Calibrator::Params params = params_from(options.preset, options.params_file);
  if (dataset.has_lidar2()) {  // DATASET.md: lidar/ with lidar2/ is lidar-lidar
    LidarPairInput input;
    input.source = options.input;
    input.default_output = (fs::path(options.input) / "calibration.yaml").string();
    input.target = dataset.target();
    input.truth = dataset.ground_truth();
    input.frames = dataset.size();
    input.read_frames = [&dataset](std::size_t count, const std::function<void(const io::Frame&)>& visit) {
      for (std::size_t i = 0; i < count; ++i) visit(dataset.load(i));
    };
    return calibrate_lidar_pair(input, lidar_pair_run(options, params));
  }
  // A dataset with the left camera alone is lidar-mono: the board by its markers.
  Calibrator calibrator = dataset.mono()
                              ? Calibrator(dataset.cameras().left, dataset.cameras().images, dataset.target(), params)
                              : Calibrator(dataset.cameras(), dataset.target(), params);
  if (dataset.mono()) std::printf("mono      left camera alone: board pose from its ArUco markers\n");

  const std::size_t count =
      options.frames > 0 ? std::min<std::size_t>(options.frames, dataset.size()) : dataset.size();
  FrameFeed feed(calibrator, {count, static_cast<std::size_t>(options.frames_ahead), dataset.mono(),
                              dataset.accumulated(), options.verbose});
  for (std::size_t i = 0; i < count; ++i) {
    // An accumulated dataset's cloud is read with the first frame of its pose only.
    feed.push([&dataset, i] {
      return dataset.accumulated() && dataset.lidar_stem(i) != dataset.stems()[i] ? dataset.load_images(i)
                                                                                   : dataset.load(i);
    });
  }
  const io::Frame last_frame = feed.finish();

  CalibrationInput input;
  input.source = options.input;
  input.default_output = (fs::path(options.input) / "calibration.yaml").string();
  input.truth = dataset.ground_truth();
  input.left_image = [&dataset](const std::string& stem) {
    const auto& stems = dataset.stems();
    const auto found = std::find(stems.begin(), stems.end(), stem);
    return found == stems.end() ? Image{} : dataset.load_images(static_cast<std::size_t>(found - stems.begin())).left;
  };
  return report_calibration(options, input, calibrator, last_frame);
}

}  // namespace

void add_calibrate_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand(
      "calibrate", "Calibrate a dataset folder or a ROS 1 recording: T_lidar_camera (T_lidar_lidar2 for a "
                   "lidar-lidar dataset)");
  auto options = std::make_shared<CalibrateOptions>();
  command->add_option("input", options->input, "dataset folder (DATASET.md) or ROS 1 .bag recording")->required();
  command->add_option("-o,--output", options->output,
                      "result YAML (default DATASET/calibration.yaml, or RECORDING_calibration.yaml beside a "
                      "recording)");
  command->add_option("--overlay", options->overlay, "overlay PNG (default beside the result)");
  command->add_option("--params", options->params_file, "parameters YAML (see --preset)")
      ->check(CLI::ExistingFile);
  command->add_option("--preset", options->preset, "parameter preset")
      ->check(CLI::IsMember({"default", "paper"}));
  command->add_option("--frames", options->frames, "use only the first N frames")
      ->check(CLI::PositiveNumber)
      ->default_str("all");
  command->add_option("--frames-ahead", options->frames_ahead,
                      "camera branches run ahead on worker threads (0: one frame at a time)")
      ->check(CLI::Range(0, 8));
  command->add_flag("-v,--verbose", options->verbose, "print why each frame was not used");
  command->add_flag("--keep-failed", options->keep_failed,
                    "write the result and exit 0 even when the scene check fails it");
  auto* recording = command->add_option_group("recording", "A ROS 1 recording's board, topics and pairing");
  recording->add_option("--target", options->target, "target.yaml of the board (default: the default board)")
      ->check(CLI::ExistingFile);
  add_recording_options(recording, options->topics, options->pairing, true);
  command->callback([&runner, options] {
    runner = [options] {
      if (is_ros1_bag(options->input)) return calibrate_recording(*options);
      const RecordingTopics& t = options->topics;
      const bool recording_options = !options->target.empty() || !t.lidar.empty() || !t.lidar2.empty() || !t.left.empty() ||
                                     !t.right.empty() || !t.left_info.empty() || !t.right_info.empty() ||
                                     options->pairing.tolerance_s != PairingParams{}.tolerance_s ||
                                     options->pairing.stereo_tolerance_s != PairingParams{}.stereo_tolerance_s;
      if (recording_options)
        throw ParamError("--target/--*-topic", "apply to a recording; " + options->input +
                                                   " is read as a dataset folder (its target.yaml names the board)");
      return calibrate_dataset(*options);
    };
  });
}

}  // namespace l2s::cli
