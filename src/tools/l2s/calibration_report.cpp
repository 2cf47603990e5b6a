// The report, overlay and result file of `l2s calibrate` (calibration_report.hpp).
#include "calibration_report.hpp"

#include "pose_printing.hpp"

#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>
#include <l2s/viz/overlay.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

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
/// nothing was checked or its image cannot be had).
Image overlay_image(const CalibrationInput& input, const Calibrator& calibrator, const Calibrator::Result& result,
                    const io::Frame& fallback) {
  const auto& kept = calibrator.check_frames();
  if (kept.empty() || !result.checked)
    return render_overlay(fallback.left, fallback.lidar, calibrator.cameras().left, result.T_lidar_camera);
  Image left = kept.back().id == fallback.stem ? fallback.left : input.left_image(kept.back().id);
  if (left.pixels.empty()) left = fallback.left;
  const std::string caption = std::string("check: ") + verdict_name(result.quality.verdict) + " | frame " +
                              kept.back().id + " | yellow/magenta: lidar depth edges, blue: image edges";
  return render_edge_overlay(left, calibrator.cameras(), kept.back().lidar, result.T_lidar_camera,
                             SceneObserver(calibrator.params().observer), caption);
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

/// The estimate, its residual and check, and its error when the input has the truth.
void print_estimate(const CalibrationInput& input, const Calibrator::Result& result) {
  print_pose("estimate", result.T_lidar_camera);
  std::printf("residual  rms %.2f mm over the hole centres of %d pose(s)\n", result.registration.rms * 1e3,
              std::max(1, result.poses_used()));
  print_uncertainty(result.joint, used_poses(result.poses));
  if (result.checked) print_quality(result);
  if (input.truth) {
    print_pose("truth", *input.truth);
    const PoseError error = pose_error(result.T_lidar_camera, *input.truth);
    std::printf("error     e_t = %.1f mm, e_r = %.3f deg\n", error.translation * 1e3,
                error.rotation * 180.0 / M_PI);
  }
}

}  // namespace

void print_frame_failure(const FrameReport& frame) {
  for (const auto& [side, branch] : {std::pair{"lidar", &frame.lidar}, std::pair{"camera", &frame.camera}}) {
    if (!branch->found)
      std::fprintf(stderr, "  frame %s %s: %s: %s\n", frame.id.c_str(), side, branch->failed_stage.c_str(),
                   branch->reason.c_str());
    else if (!branch->note.empty())
      std::fprintf(stderr, "  frame %s %s: note: %s\n", frame.id.c_str(), side, branch->note.c_str());
  }
}

int report_calibration(const CalibrateOptions& options, const CalibrationInput& input, const Calibrator& calibrator,
                       const io::Frame& last_frame) {
  const Calibrator::Result result = calibrator.result();
  print_counts(result);
  if (result.poses.size() > 1 || !result.moving_frames.empty()) print_poses(result);
  if (!result.found) {
    print_calibration_failure(result, options.verbose);
    return 1;
  }

  const std::string output = options.output.empty() ? input.default_output : options.output;
  const std::string overlay = options.overlay.empty()
                                  ? (fs::path(output).replace_extension("").string() + "_overlay.png")
                                  : options.overlay;
  // The overlay is written either way: it is how a user sees why a check failed.
  io::write_png(overlay, overlay_image(input, calibrator, result, last_frame));
  const bool failed = result.checked && result.quality.verdict == CalibrationCheck::Verdict::Failed;
  if (!failed || options.keep_failed)
    io::write_calibration_result(output, result, input.source,
                                 options.params_file.empty() ? options.preset : options.params_file);
  print_estimate(input, result);
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

}  // namespace l2s::cli
