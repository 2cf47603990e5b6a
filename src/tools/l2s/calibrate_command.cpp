// l2s calibrate DATASET: streams a dataset folder through the Calibrator,
// writes the result (atomically) and an overlay image, prints a short report.

#include "commands.hpp"
#include "progress_bar.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/metrics.hpp>
#include <l2s/viz/overlay.hpp>
#include <l2s/pose.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

struct CalibrateOptions {
  std::string dataset;
  std::string output;
  std::string overlay;
  std::string params_file;
  std::string preset = "default";
  int frames = 0;
  bool verbose = false;
};

void print_pose(const char* label, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.rotation());
  std::printf("%-10s t = (%8.4f, %8.4f, %8.4f) m   rpy = (%8.4f, %8.4f, %8.4f) rad\n", label, t.x(),
              t.y(), t.z(), rpy[0], rpy[1], rpy[2]);
}

void print_frame_failure(const FrameReport& frame) {
  for (const auto& [side, branch] : {std::pair{"lidar", &frame.lidar}, std::pair{"camera", &frame.camera}}) {
    if (!branch->found)
      std::fprintf(stderr, "  frame %s %s: %s: %s\n", frame.id.c_str(), side, branch->failed_stage.c_str(),
                   branch->reason.c_str());
    else if (!branch->note.empty())
      std::fprintf(stderr, "  frame %s %s: note: %s\n", frame.id.c_str(), side, branch->note.c_str());
  }
}

int run_calibrate(const CalibrateOptions& options) {
  const auto dataset = io::Dataset::open(options.dataset);
  for (const std::string& warning : dataset.warnings())
    std::fprintf(stderr, "l2s: warning: %s\n", warning.c_str());
  const Calibrator::Params params = options.params_file.empty()
                                        ? Calibrator::Params::preset(options.preset)
                                        : io::read_calibrator_params(options.params_file);
  Calibrator calibrator(dataset.cameras(), dataset.target(), params);

  const std::size_t count =
      options.frames > 0 ? std::min<std::size_t>(options.frames, dataset.size()) : dataset.size();
  ProgressBar progress("calibrate", count);
  io::Frame last_frame;
  std::size_t doubtful_rings = 0;
  std::string first_doubt;
  for (std::size_t i = 0; i < count; ++i) {
    io::Frame frame = dataset.load(i);
    if (frame.ring_recovery && (frame.ring_recovery->doubtful ||
                                frame.ring_recovery->structure == io::ScanStructure::RingFree)) {
      if (doubtful_rings++ == 0) first_doubt = frame.stem + ": " + frame.ring_recovery->summary();
    }
    const FrameReport report = calibrator.add(frame.lidar, frame.left, frame.right, frame.stem);
    if (options.verbose) print_frame_failure(report);
    progress.update(i + 1);
    last_frame = std::move(frame);
  }
  progress.finish();
  if (doubtful_rings > 0)
    std::fprintf(stderr, "l2s: warning: %zu of %zu sweeps have no ring field and a doubtful or no ring structure (first %s)\n",
                 doubtful_rings, count, first_doubt.c_str());

  const Calibrator::Result result = calibrator.result();
  std::printf("frames    %d: lidar found the board in %d, camera in %d\n", result.frames_added,
              result.lidar_frames, result.camera_frames);
  std::printf("time      %.1f ms/frame lidar, %.1f ms/frame camera\n",
              result.lidar_ms / std::max(1, result.frames_added),
              result.camera_ms / std::max(1, result.frames_added));
  if (!result.found) {
    if (!options.verbose) {
      // Without -v the user still needs the first reason per side to act on.
      for (const auto& frame : result.frames)
        if (!frame.used()) {
          print_frame_failure(frame);
          break;
        }
    }
    std::fprintf(stderr, "l2s: calibration failed: %s\n", result.reason.c_str());
    return 1;
  }

  const std::string output =
      options.output.empty() ? (fs::path(options.dataset) / "calibration.yaml").string() : options.output;
  io::write_calibration_result(output, result, options.dataset,
                               options.params_file.empty() ? options.preset : options.params_file);
  const std::string overlay = options.overlay.empty()
                                  ? (fs::path(output).replace_extension("").string() + "_overlay.png")
                                  : options.overlay;
  io::write_png(overlay, render_overlay(last_frame.left, last_frame.lidar, dataset.cameras().left,
                                        result.T_lidar_camera));

  print_pose("estimate", result.T_lidar_camera);
  std::printf("residual  rms %.2f mm over the four hole centres\n", result.registration.rms * 1e3);
  if (const auto truth = dataset.ground_truth()) {
    print_pose("truth", *truth);
    const PoseError error = pose_error(result.T_lidar_camera, *truth);
    std::printf("error     e_t = %.1f mm, e_r = %.3f deg\n", error.translation * 1e3,
                error.rotation * 180.0 / M_PI);
  }
  std::printf("wrote     %s\n          %s\n", output.c_str(), overlay.c_str());
  return 0;
}

}  // namespace

void add_calibrate_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand("calibrate", "Calibrate a dataset folder: T_lidar_camera");
  auto options = std::make_shared<CalibrateOptions>();
  command->add_option("dataset", options->dataset, "dataset folder (DATASET.md)")->required();
  command->add_option("-o,--output", options->output, "result YAML (default DATASET/calibration.yaml)");
  command->add_option("--overlay", options->overlay, "overlay PNG (default beside the result)");
  command->add_option("--params", options->params_file, "parameters YAML (see --preset)")
      ->check(CLI::ExistingFile);
  command->add_option("--preset", options->preset, "parameter preset")
      ->check(CLI::IsMember({"default", "paper"}));
  command->add_option("--frames", options->frames, "use only the first N frames")->check(CLI::PositiveNumber);
  command->add_flag("-v,--verbose", options->verbose, "print why each frame was not used");
  command->callback([&runner, options] { runner = [options] { return run_calibrate(*options); }; });
}

}  // namespace l2s::cli
