// l2s detect DATASET --frame STEM: one frame through one branch (or both),
// showing what every stage found and the thresholds it used, with debug
// pictures. This is how a user finds out why the board is not detected.

#include "commands.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/viz/inspection_images.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/mono_board_detector.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

struct DetectOptions {
  std::string dataset;
  std::string frame;
  std::string sensor = "both";
  std::string preset = "default";
  std::string params_file;
  std::string output;
};

// The frame by stem; a plain number that is not a stem is taken as an index.
std::size_t find_frame(const io::Dataset& dataset, const std::string& frame) {
  const auto& stems = dataset.stems();
  if (frame.empty()) return 0;
  const auto it = std::find(stems.begin(), stems.end(), frame);
  if (it != stems.end()) return static_cast<std::size_t>(it - stems.begin());
  if (!frame.empty() && frame.find_first_not_of("0123456789") == std::string::npos &&
      frame.size() < 9) {
    const std::size_t index = std::stoul(frame);
    if (index < stems.size()) return index;
  }
  throw FileError(dataset.folder(), "no frame '" + frame + "' (" + std::to_string(stems.size()) +
                                        " frames, " + stems.front() + " .. " + stems.back() + ")");
}

// A ring-free sweep is detected as the Calibrator does: with the next
// sweeps of its window accumulated (ring_free_frames, as many as the dataset
// has); an accumulated cloud (`lidar: accumulated`) as it stands.
LidarInspection inspect_lidar_frame(const io::Dataset& dataset, const io::Frame& frame, std::size_t index,
                                    const Calibrator::Params& params) {
  std::printf("lidar   path: %s\n", frame_path(frame, params).c_str());
  const bool ring_free = lidar_path(frame.lidar, params).ring_free;
  if (dataset.accumulated() && !frame.lidar_stem.empty()) {
    std::printf("lidar   accumulated cloud lidar/%s.pcd, detected as it stands\n", frame.lidar_stem.c_str());
    return ring_free ? inspect_lidar(std::vector<LidarCloud>{frame.lidar}, dataset.target(), params)
                     : inspect_lidar(frame.lidar, dataset.target(), params);
  }
  if (!ring_free) return inspect_lidar(frame.lidar, dataset.target(), params);
  std::vector<LidarCloud> sweeps{frame.lidar};
  for (std::size_t i = index + 1; i < dataset.size() && sweeps.size() < static_cast<std::size_t>(params.ring_free_frames);
       ++i)
    sweeps.push_back(dataset.load(i).lidar);
  std::printf("lidar   ring-free scan: %zu sweeps accumulated from %s on (ring_free_frames %d)\n", sweeps.size(),
              frame.stem.c_str(), params.ring_free_frames);
  return inspect_lidar(sweeps, dataset.target(), params);
}

std::string write_image(const fs::path& folder, const std::string& name, const Image& image) {
  if (image.empty()) return {};
  const std::string path = (folder / name).string();
  io::write_png(path, image);
  return path;
}

/// A mono dataset's camera side: the markers found, the pose's fit, the centres.
BranchReport detect_mono(const io::Dataset& dataset, const io::Frame& frame, const Calibrator::Params& params) {
  const MonoBoardDetector detector(dataset.cameras().left, dataset.cameras().images, dataset.target(), params.mono);
  const MonoBoardDetector::Result result = detector.detect(frame.left);
  std::printf("camera  mono (%s images): %zu of the target's %d markers found",
              dataset.cameras().images == ImageKind::Raw ? "raw" : "rectified", result.markers.size(),
              result.markers_expected);
  for (std::size_t i = 0; i < result.markers.size(); ++i) std::printf("%s%d", i ? ", " : " (ids ", result.markers[i].id);
  std::printf("%s\n", result.markers.empty() ? "" : ")");
  BranchReport report;
  report.found = result.found;
  report.failed_stage = result.failed_stage;
  report.reason = result.reason;
  report.centers = result.centers;
  if (!result.markers.empty())
    std::printf("        marker corners rms %.3f px under the PnP pose (limit %.2f px: corner noise %.3f px measured on "
                "the markers' edges, %.1f mm placement tolerance)\n",
                result.marker_rms_px, result.marker_rms_limit_px, result.corner_sigma_px,
                params.mono.marker_placement_tolerance * 1e3);
  for (const auto& placement : result.placements)
    if (placement.placed)
      std::printf("        marker %-4d %5.1f mm off its place (x %+.1f, y %+.1f mm), turned %+.2f deg, corners %.2f px%s\n",
                  placement.id, placement.offset.norm() * 1e3, placement.offset.x() * 1e3, placement.offset.y() * 1e3,
                  placement.rotation_deg, placement.rms_px, placement.left_out ? ": left out of the pose" : "");
  if (result.rim_refined) std::printf("        refined with the hole rims: rms %.3f px\n", result.rim_rms_px);
  if (!result.note.empty()) std::printf("        note: %s\n", result.note.c_str());
  if (result.found)
    for (int h = 0; h < 4; ++h)
      std::printf("        %s  (%8.4f, %8.4f, %8.4f) m\n", hole_name(static_cast<Hole>(h)), result.centers[h].x(),
                  result.centers[h].y(), result.centers[h].z());
  std::printf("\n");
  return report;
}

/// A stereo board that carries markers: the left image alone, by its
/// markers, as an independent check of the stereo branch's centres.
void cross_check_with_markers(const io::Dataset& dataset, const io::Frame& frame, const Calibrator::Params& params,
                              const BranchReport& stereo) {
  std::printf("cross-check: the board's markers in the left image alone\n");
  const BranchReport mono = detect_mono(dataset, frame, params);
  if (!mono.found || !stereo.found) return;
  std::printf("        markers - stereo:");
  for (int h = 0; h < 4; ++h)
    std::printf(" %s %.1f mm", hole_name(static_cast<Hole>(h)), (mono.centers[h] - stereo.centers[h]).norm() * 1e3);
  std::printf("\n\n");
}

int run_detect(const DetectOptions& options) {
  const auto dataset = open_dataset_warning(options.dataset);
  const Calibrator::Params params = params_from(options.preset, options.params_file);
  const io::Frame frame = dataset.load(find_frame(dataset, options.frame));
  const fs::path debug_dir =
      options.output.empty() ? fs::path(options.dataset) / "debug" : fs::path(options.output);
  fs::create_directories(debug_dir);
  const bool lidar = options.sensor != "camera", camera = options.sensor != "lidar";

  const std::string params_name =
      options.params_file.empty() ? "preset " + options.preset : options.params_file;
  std::printf("frame   %s of %s (%s)\n", frame.stem.c_str(), options.dataset.c_str(),
              params_name.c_str());
  if (frame.ring_recovery) {  // no ring field in the sweep: say how its rings were found
    std::printf("rings   %s\n", frame.ring_recovery->summary().c_str());
    if (frame.ring_recovery->structure == io::ScanStructure::RingFree || frame.ring_recovery->doubtful)
      std::fprintf(stderr, "l2s: warning: ring structure of frame %s: %s\n", frame.stem.c_str(),
                   frame.ring_recovery->doubtful ? frame.ring_recovery->doubt.c_str()
                                                 : frame.ring_recovery->structure_reason.c_str());
  }
  const Target& target = dataset.target();
  std::printf("target  %.3f x %.3f m board, holes r %.3f m on %.3f x %.3f m%s\n\n",
              target.board_width, target.board_height, target.hole_radius, target.hole_spacing_x,
              target.hole_spacing_y,
              dataset.has_target_file() ? "" : " (defaults: no target.yaml)");

  std::vector<std::string> failures, written;
  if (lidar) {
    const LidarInspection inspection = inspect_lidar_frame(dataset, frame, find_frame(dataset, options.frame), params);
    std::printf("%s\n", describe(inspection, params).c_str());
    written.push_back(write_image(debug_dir, frame.stem + "_lidar.png",
                                  render_lidar_inspection(inspection, target)));
    if (!inspection.report.found)
      failures.push_back("lidar: " + inspection.report.failed_stage + ": " +
                         inspection.report.reason);
  }
  if (camera && dataset.mono()) {
    const BranchReport report = detect_mono(dataset, frame, params);
    if (!report.found) failures.push_back("camera: " + report.failed_stage + ": " + report.reason);
  } else if (camera) {
    const CameraInspection inspection =
        inspect_camera(frame.left, frame.right, dataset.cameras(), target, params);
    std::printf("%s\n", describe(inspection, params, dataset.cameras()).c_str());
    written.push_back(
        write_image(debug_dir, frame.stem + "_camera.png",
                    render_camera_inspection(frame.left, inspection, dataset.cameras(), target)));
    written.push_back(
        write_image(debug_dir, frame.stem + "_disparity.png", render_disparity(inspection)));
    if (!inspection.report.found)
      failures.push_back("camera: " + inspection.report.failed_stage + ": " +
                         inspection.report.reason);
    if (target.markers) cross_check_with_markers(dataset, frame, params, inspection.report);
  }

  const char* prefix = "wrote   ";
  for (const auto& path : written)
    if (!path.empty()) std::printf("%s%s\n", prefix, path.c_str()), prefix = "        ";
  if (failures.empty()) return 0;
  std::string reason;
  for (const auto& failure : failures) reason += (reason.empty() ? "" : "; ") + failure;
  std::fflush(stdout);
  std::fprintf(stderr, "l2s: board not found in frame %s: %s\n", frame.stem.c_str(),
               reason.c_str());
  return 1;
}

}  // namespace

void add_detect_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand(
      "detect",
      "Run one frame through the lidar and/or camera branch and show why the board is (not) found");
  auto options = std::make_shared<DetectOptions>();
  command->add_option("dataset", options->dataset, "dataset folder (DATASET.md)")->required();
  command->add_option("--frame", options->frame, "frame stem, or index (default: the first frame)");
  command->add_option("--sensor", options->sensor, "branch to run")
      ->check(CLI::IsMember({"lidar", "camera", "both"}));
  command->add_option("--preset", options->preset, "parameter preset")
      ->check(CLI::IsMember({"default", "paper"}));
  command->add_option("--params", options->params_file, "parameters YAML (overrides --preset)")
      ->check(CLI::ExistingFile);
  command->add_option("-o,--output", options->output,
                      "folder for the debug images (default DATASET/debug)");
  command->callback([&runner, options] { runner = [options] { return run_detect(*options); }; });
}

}  // namespace l2s::cli
