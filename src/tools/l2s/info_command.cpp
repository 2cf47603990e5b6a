// l2s info DATASET: what a dataset folder holds, checked as the calibrator reads it
// (a ROS 1 bag instead: recording_info.cpp).

#include "commands.hpp"

#include <l2s/io/dataset.hpp>
#include <l2s/io/dataset_yaml.hpp>
#include <l2s/io/ring_recovery.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

namespace l2s::cli {
namespace {

// "16 rings from the ring field (laser model: 16 rings)", the structure and
// path lines; warnings for doubtful or ring-free sweeps go to stderr.
void print_rings(const io::Frame& frame) {
  std::set<int> rings(frame.lidar.ring.begin(), frame.lidar.ring.end());
  io::RingRecoveryReport report;
  if (frame.ring_recovery) {
    report = *frame.ring_recovery;
  } else {  // a ring field: compare it with what the laser model recovers
    LidarCloud copy;
    copy.points = frame.lidar.points;
    report = io::recover_ring_structure(copy);
  }
  std::printf("    rings: %zu distinct in the sweep, from %s", rings.size(),
              io::to_string(frame.ring_source).c_str());
  if (frame.ring_source == io::RingSource::Field)
    std::printf(" (the laser model recovers %d)", report.rings);
  std::printf("\n    structure: %s\n", report.summary().c_str());
  std::printf("    path: %s\n", frame_path(frame, Calibrator::Params{}).c_str());
  if (report.structure == io::ScanStructure::RingFree)
    std::fprintf(stderr, "l2s: warning: %s: sweep looks ring-free: %s\n", frame.stem.c_str(),
                 report.structure_reason.c_str());
  else if (report.doubtful)
    std::fprintf(stderr, "l2s: warning: %s: ring structure doubtful: %s\n", frame.stem.c_str(),
                 report.doubt.c_str());
}

// How the lidar files pair with the frames (DATASET.md v3 `lidar:`).
void print_lidar_form(const io::Dataset& dataset) {
  if (!dataset.accumulated()) {
    std::printf("lidar     sweeps: one per frame, matched by stem\n");
    return;
  }
  std::printf("lidar     accumulated (dataset.yaml): %zu cloud(s), each of a static pose beside the image frames "
              "from its stem to the next cloud's:",
              dataset.lidar_stems().size());
  std::size_t listed = 0;
  for (const std::string& stem : dataset.lidar_stems()) {
    std::size_t frames = 0;
    for (std::size_t i = 0; i < dataset.size(); ++i) frames += dataset.lidar_stem(i) == stem;
    if (listed++ < 5) std::printf(" %s (%zu frames)", stem.c_str(), frames);
  }
  if (listed > 5) std::printf(" ...");
  std::printf("\n");
  const auto before = static_cast<std::size_t>(
      std::find_if(dataset.stems().begin(), dataset.stems().end(), [&](const std::string& stem) {
        return stem == dataset.lidar_stems().front();
      }) - dataset.stems().begin());
  if (before > 0) std::printf("          %zu image frame(s) before the first cloud have no lidar\n", before);
}

int print_info(const std::string& folder, bool load_all) {
  const auto dataset = io::Dataset::open(folder);
  for (const std::string& warning : dataset.warnings())
    std::fprintf(stderr, "l2s: warning: %s\n", warning.c_str());
  const auto& left = dataset.cameras().left;
  const Target& target = dataset.target();
  std::printf("dataset   %s\n", folder.c_str());
  if (dataset.has_lidar2()) {
    std::printf("sensors   lidar/ and lidar2/: a lidar-lidar dataset (T_lidar_lidar2), no cameras\n");
  } else {
    std::printf("images    %s%s\n", io::to_string(dataset.cameras().images).c_str(),
                dataset.has_dataset_file() ? " (dataset.yaml)" : " (default: no dataset.yaml)");
    std::printf("cameras   %dx%d px, fx %.1f px, fy %.1f px, c (%.1f, %.1f), baseline %.4f m\n", left.width,
                left.height, left.fx(), left.fy(), left.cx(), left.cy(), dataset.cameras().baseline());
  }
  std::printf("target    %.3f x %.3f x %.3f m board, holes r %.3f m on %.3f x %.3f m%s\n",
              target.board_width, target.board_height, target.board_thickness, target.hole_radius,
              target.hole_spacing_x, target.hole_spacing_y,
              dataset.has_target_file() ? "" : " (defaults: no target.yaml)");
  std::printf("frames    %zu (%s .. %s)\n", dataset.size(), dataset.stems().front().c_str(),
              dataset.stems().back().c_str());
  print_lidar_form(dataset);

  // Loading every frame proves each file is readable; by default only the
  // first (of an accumulated dataset: the first lidar file's frame).
  std::size_t first = 0;
  while (first + 1 < dataset.size() && dataset.lidar_stem(first).empty()) ++first;
  const std::size_t count = load_all ? dataset.size() : first + 1;
  for (std::size_t i = load_all ? 0 : first; i < count; ++i) {
    if (dataset.accumulated() && dataset.lidar_stem(i) != dataset.stems()[i]) {
      const std::string& cloud = dataset.lidar_stem(i);
      const auto frame = dataset.load_images(i);
      std::printf("  %s: images %s, %s\n", frame.stem.c_str(), frame.left.channels == 1 ? "gray" : "colour",
                  cloud.empty() ? "no lidar file covers it" : ("with lidar/" + cloud + ".pcd").c_str());
      continue;
    }
    const auto frame = dataset.load(i);
    const auto finite = std::count_if(frame.lidar.points.begin(), frame.lidar.points.end(),
                                      [](const Eigen::Vector3d& p) { return p.allFinite(); });
    if (dataset.has_lidar2())
      std::printf("  %s: %zu lidar points (%ld finite), lidar2 %zu points, rings %s\n", frame.stem.c_str(),
                  frame.lidar.size(), static_cast<long>(finite), frame.lidar2.size(),
                  frame.lidar2.has_ring() ? io::to_string(frame.lidar2_ring_source).c_str() : "none (ring-free)");
    else
      std::printf("  %s: %zu lidar points (%ld finite), images %s\n", frame.stem.c_str(), frame.lidar.size(),
                  static_cast<long>(finite), frame.left.channels == 1 ? "gray" : "colour");
    print_rings(frame);
  }
  if (const auto truth = dataset.ground_truth()) {
    const Eigen::Vector3d t = truth->translation();
    const Eigen::Vector3d rpy = roll_pitch_yaw(truth->rotation());
    std::printf("truth     %s t = (%.4f, %.4f, %.4f) m, roll/pitch/yaw = (%.4f, %.4f, %.4f) rad\n",
                dataset.has_lidar2() ? "T_lidar_lidar2" : "T_lidar_camera", t.x(), t.y(), t.z(), rpy[0], rpy[1],
                rpy[2]);
  }
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand("info", "Summarise a dataset folder (DATASET.md) or a recording (ROS 1 bag)");
  auto folder = std::make_shared<std::string>();
  auto load_all = std::make_shared<bool>(false);
  command->add_option("dataset", *folder, "dataset folder, or a recording: a ROS 1 .bag file")->required();
  command->add_flag("--all", *load_all, "load every frame, not only the first");
  command->callback([&runner, folder, load_all] {
    runner = [folder, load_all] {
      return is_ros1_bag(*folder) ? print_recording_info(*folder) : print_info(*folder, *load_all);
    };
  });
}

}  // namespace l2s::cli
