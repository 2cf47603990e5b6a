// l2s calibrate DATASET: streams a dataset folder through the Calibrator,
// writes the result (atomically) and an overlay image, prints a short report
// with the verdict of the scene check. A failed check exits non-zero and
// writes no result (unless --keep-failed); a suspect one warns loudly.

#include "commands.hpp"
#include "pose_printing.hpp"
#include "progress_bar.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/metrics.hpp>
#include <l2s/viz/overlay.hpp>
#include <l2s/pose.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
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
  int frames_ahead = 2;
  bool verbose = false;
  bool keep_failed = false;
};

void print_frame_failure(const FrameReport& frame) {
  for (const auto& [side, branch] : {std::pair{"lidar", &frame.lidar}, std::pair{"camera", &frame.camera}}) {
    if (!branch->found)
      std::fprintf(stderr, "  frame %s %s: %s: %s\n", frame.id.c_str(), side, branch->failed_stage.c_str(),
                   branch->reason.c_str());
    else if (!branch->note.empty())
      std::fprintf(stderr, "  frame %s %s: note: %s\n", frame.id.c_str(), side, branch->note.c_str());
  }
}

void print_quality(const Calibrator::Result& result) {
  const CalibrationCheck::Report& q = result.quality;
  for (const auto& note : result.notes) std::printf("note      %s\n", note.c_str());
  std::printf("check     %s: edges %.3f of %d on image edges, overlay %.1f px (%.2f deg) from its best; board "
              "%+.1f mm, tilt %.2f deg (%.0f ms)\n",
              verdict_name(q.verdict), q.scores.edge_score, q.scores.edge_points, q.misalignment_px,
              q.misalignment * 180.0 / M_PI, q.scores.plane_offset * 1e3, q.scores.plane_tilt * 180.0 / M_PI,
              q.milliseconds);
  if (q.verdict == CalibrationCheck::Verdict::Suspect) {
    std::fprintf(stderr, "\n  *** WARNING: the scene check finds this calibration SUSPECT ***\n");
    for (const auto& reason : q.reasons) std::fprintf(stderr, "  *** %s\n", reason.c_str());
    std::fprintf(stderr, "  *** look at the overlay before using it\n\n");
  }
}

/// The check's picture of the last checked frame (or of `fallback` when
/// nothing was checked).
Image overlay_image(const io::Dataset& dataset, const Calibrator& calibrator, const Calibrator::Result& result,
                    const io::Frame& fallback) {
  const auto& kept = calibrator.check_frames();
  if (kept.empty() || !result.checked)
    return render_overlay(fallback.left, fallback.lidar, dataset.cameras().left, result.T_lidar_camera);
  const auto& stems = dataset.stems();
  const auto stem = std::find(stems.begin(), stems.end(), kept.back().id);
  const io::Frame frame = stem == stems.end() ? fallback : dataset.load(static_cast<std::size_t>(stem - stems.begin()));
  const std::string caption = std::string("check: ") + verdict_name(result.quality.verdict) + " | frame " +
                              kept.back().id + " | yellow/magenta: lidar depth edges, blue: image edges";
  return render_edge_overlay(frame.left, dataset.cameras(), kept.back().lidar, result.T_lidar_camera,
                             SceneObserver(calibrator.params().observer), caption);
}

/// One frame read and, for a stereo dataset, its camera branch run.
struct PreparedFrame {
  io::Frame frame;
  std::optional<BranchReport> camera;
};

/// Streams the first `count` frames into the calibrator; returns the last
/// one (the overlay's fallback). Warns once about sweeps whose rings had to
/// be recovered and look doubtful.
///
/// Frames are read, and a stereo frame's camera branch run, `frames_ahead`
/// frames ahead on worker threads, while this thread runs each frame's lidar
/// branch and accumulates the frames in order (Calibrator::camera_branch()
/// reads only what the calibrator was built with). The camera branch of one
/// frame keeps about one core busy (its stereo matching parallelises little),
/// so on two cores two frames in flight take a third off the time per frame
/// (setting 1, 30 frames, runs interleaved with --frames-ahead 0: 7.8 ->
/// 5.1 s). The result is the one add(lidar, left, right) gives frame by
/// frame; a frame that cannot be read throws in order, as before. 0 frames
/// ahead: one frame at a time, its two branches side by side
/// (Calibrator::add).
io::Frame add_frames(const io::Dataset& dataset, Calibrator& calibrator, std::size_t count, bool verbose,
                     std::size_t frames_ahead) {
  ProgressBar progress("calibrate", count);
  io::Frame last_frame;
  std::size_t doubtful_rings = 0;
  std::string first_doubt;
  const bool stereo = !dataset.mono() && frames_ahead > 0;
  // An accumulated dataset's cloud is read with the first frame of its pose only.
  const auto read = [&dataset](std::size_t i) {
    return dataset.accumulated() && dataset.lidar_stem(i) != dataset.stems()[i] ? dataset.load_images(i)
                                                                                : dataset.load(i);
  };
  const auto prepare = [&read, &calibrator, stereo](std::size_t i) {
    PreparedFrame prepared{read(i), std::nullopt};
    if (stereo) prepared.camera = calibrator.camera_branch(prepared.frame.left, prepared.frame.right);
    return prepared;
  };
  std::deque<std::future<PreparedFrame>> ahead;
  std::size_t next = 0;
  const auto launch = [&] {
    const auto policy = frames_ahead > 0 ? std::launch::async : std::launch::deferred;
    while (next < count && ahead.size() < std::max<std::size_t>(frames_ahead, 1))
      ahead.push_back(std::async(policy, prepare, next++));
  };
  // Workers still running when an exception leaves finish before the
  // dataset and calibrator they use are gone: the futures' destructors wait.
  launch();
  AccumulatedLidar pose_cloud;  // `lidar: accumulated`: the cloud of the pose being added, detected once
  LidarCloud pose_points;
  for (std::size_t i = 0; i < count; ++i) {
    PreparedFrame prepared = ahead.front().get();
    ahead.pop_front();
    launch();
    io::Frame& frame = prepared.frame;
    const bool accumulated = dataset.accumulated() && !frame.lidar_stem.empty();
    if (accumulated && frame.lidar_stem == frame.stem) {
      pose_cloud = calibrator.detect_accumulated(frame.lidar);
      pose_points = std::move(frame.lidar);
    }
    if (frame.ring_recovery && (frame.ring_recovery->doubtful ||
                                frame.ring_recovery->structure == io::ScanStructure::RingFree)) {
      if (doubtful_rings++ == 0) first_doubt = frame.stem + ": " + frame.ring_recovery->summary();
    }
    const FrameReport report =
        accumulated ? (prepared.camera   ? calibrator.add(pose_cloud, *prepared.camera, frame.stem)
                       : dataset.mono() ? calibrator.add(pose_cloud, frame.left, frame.stem)
                                        : calibrator.add(pose_cloud, frame.left, frame.right, frame.stem))
        : prepared.camera ? calibrator.add(frame.lidar, *prepared.camera, frame.stem)
        : dataset.mono()  ? calibrator.add(frame.lidar, frame.left, frame.stem)
                          : calibrator.add(frame.lidar, frame.left, frame.right, frame.stem);
    if (verbose) print_frame_failure(report);
    progress.update(i + 1);
    last_frame = std::move(frame);
  }
  if (dataset.accumulated() && !last_frame.lidar_stem.empty()) last_frame.lidar = std::move(pose_points);
  progress.finish();
  if (doubtful_rings > 0)
    std::fprintf(stderr, "l2s: warning: %zu of %zu sweeps have no ring field and a doubtful or no ring structure (first %s)\n",
                 doubtful_rings, count, first_doubt.c_str());
  return last_frame;
}

void print_counts(const Calibrator::Result& result) {
  for (const auto& note : result.notes)
    if (!result.checked) std::printf("note      %s\n", note.c_str());
  std::printf("frames    %d: lidar found the board in %d, camera in %d\n", result.frames_added,
              result.lidar_frames, result.camera_frames);
  std::printf("time      %.1f ms/frame lidar, %.1f ms/frame camera\n",
              result.lidar_ms / std::max(1, result.frames_added),
              result.camera_ms / std::max(1, result.frames_added));
}

/// Why the calibration failed. Without -v the user still needs the first
/// reason per side to act on.
void print_calibration_failure(const Calibrator::Result& result, bool verbose) {
  if (!verbose) {
    for (const auto& frame : result.frames)
      if (!frame.used()) {
        print_frame_failure(frame);
        break;
      }
  }
  std::fprintf(stderr, "l2s: calibration failed: %s\n", result.reason.c_str());
}

/// The estimate, its residual and check, and its error when the dataset has the truth.
void print_estimate(const io::Dataset& dataset, const Calibrator::Result& result) {
  print_pose("estimate", result.T_lidar_camera);
  std::printf("residual  rms %.2f mm over the hole centres of %d pose(s)\n", result.registration.rms * 1e3,
              std::max(1, result.poses_used()));
  print_uncertainty(result.joint, used_poses(result.poses));
  if (result.checked) print_quality(result);
  if (const auto truth = dataset.ground_truth()) {
    print_pose("truth", *truth);
    const PoseError error = pose_error(result.T_lidar_camera, *truth);
    std::printf("error     e_t = %.1f mm, e_r = %.3f deg\n", error.translation * 1e3,
                error.rotation * 180.0 / M_PI);
  }
}

int run_calibrate(const CalibrateOptions& options) {
  const auto dataset = open_dataset_warning(options.dataset);
  const Calibrator::Params params = params_from(options.preset, options.params_file);
  if (dataset.has_lidar2())  // DATASET.md: lidar/ with lidar2/ is lidar-lidar
    return calibrate_lidar_pair(dataset, {params, options.params_file.empty() ? options.preset : options.params_file,
                                          options.output, options.frames, options.verbose});
  // A dataset with the left camera alone is lidar-mono: the board by its markers.
  Calibrator calibrator = dataset.mono()
                              ? Calibrator(dataset.cameras().left, dataset.cameras().images, dataset.target(), params)
                              : Calibrator(dataset.cameras(), dataset.target(), params);
  if (dataset.mono()) std::printf("mono      left camera alone: board pose from its ArUco markers\n");

  const std::size_t count =
      options.frames > 0 ? std::min<std::size_t>(options.frames, dataset.size()) : dataset.size();
  const io::Frame last_frame =
      add_frames(dataset, calibrator, count, options.verbose, static_cast<std::size_t>(options.frames_ahead));
  const Calibrator::Result result = calibrator.result();
  print_counts(result);
  if (result.poses.size() > 1 || !result.moving_frames.empty()) print_poses(result);
  if (!result.found) {
    print_calibration_failure(result, options.verbose);
    return 1;
  }

  const std::string output =
      options.output.empty() ? (fs::path(options.dataset) / "calibration.yaml").string() : options.output;
  const std::string overlay = options.overlay.empty()
                                  ? (fs::path(output).replace_extension("").string() + "_overlay.png")
                                  : options.overlay;
  // The overlay is written either way: it is how a user sees why a check failed.
  io::write_png(overlay, overlay_image(dataset, calibrator, result, last_frame));
  const bool failed = result.checked && result.quality.verdict == CalibrationCheck::Verdict::Failed;
  if (!failed || options.keep_failed)
    io::write_calibration_result(output, result, options.dataset,
                                 options.params_file.empty() ? options.preset : options.params_file);
  print_estimate(dataset, result);
  if (failed) {
    std::fprintf(stderr, "l2s: the scene check FAILED this calibration:\n");
    for (const auto& reason : result.quality.reasons) std::fprintf(stderr, "  - %s\n", reason.c_str());
    if (!options.keep_failed) {
      std::fprintf(stderr, "l2s: no result written (--keep-failed writes it anyway); overlay: %s\n", overlay.c_str());
      return 1;
    }
    std::fprintf(stderr, "l2s: --keep-failed: writing it anyway\n");
  }
  std::printf("wrote     %s\n          %s\n", output.c_str(), overlay.c_str());
  return 0;
}

}  // namespace

void add_calibrate_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand("calibrate", "Calibrate a dataset folder: T_lidar_camera (T_lidar_lidar2 for a lidar-lidar dataset)");
  auto options = std::make_shared<CalibrateOptions>();
  command->add_option("dataset", options->dataset, "dataset folder (DATASET.md)")->required();
  command->add_option("-o,--output", options->output, "result YAML (default DATASET/calibration.yaml)");
  command->add_option("--overlay", options->overlay, "overlay PNG (default beside the result)");
  command->add_option("--params", options->params_file, "parameters YAML (see --preset)")
      ->check(CLI::ExistingFile);
  command->add_option("--preset", options->preset, "parameter preset")
      ->check(CLI::IsMember({"default", "paper"}));
  command->add_option("--frames", options->frames, "use only the first N frames")->check(CLI::PositiveNumber);
  command->add_option("--frames-ahead", options->frames_ahead,
                      "camera branches run ahead on worker threads (0: one frame at a time)")
      ->check(CLI::Range(0, 8));
  command->add_flag("-v,--verbose", options->verbose, "print why each frame was not used");
  command->add_flag("--keep-failed", options->keep_failed,
                    "write the result and exit 0 even when the scene check fails it");
  command->callback([&runner, options] { runner = [options] { return run_calibrate(*options); }; });
}

}  // namespace l2s::cli
