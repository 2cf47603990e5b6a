// l2s extract RECORDING OUT_DIR: a ROS 1 bag written as a dataset folder
// (DATASET.md), its sweeps paired with its images in time.

#include "commands.hpp"

#include <l2s/io/target_yaml.hpp>
#include <l2s/recording/dataset_extraction.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <string>

namespace l2s::cli {
namespace {

struct ExtractRun {
  std::string recording, folder, target;
  ExtractionOptions options;
};

int extract(const ExtractRun& run) {
  ExtractionOptions options = run.options;
  if (!run.target.empty()) options.target = io::read_target(run.target);
  const Ros1Bag bag(run.recording);
  const ExtractionReport report = extract_dataset(bag, run.folder, options);
  std::printf("recording %s\n", run.recording.c_str());
  print_recording_topics(report.topics, report.raw_images);
  std::printf("frames    %zu of %zu sweeps paired (tolerance %.1f ms)\n", report.frames, report.sweeps,
              report.tolerance_s * 1e3);
  const std::size_t shown = 10;
  for (std::size_t k = 0; k < report.dropped.size() && k < shown; ++k)
    std::printf("  left out: %s\n", report.dropped[k].c_str());
  if (report.dropped.size() > shown) std::printf("  ... and %zu more\n", report.dropped.size() - shown);
  std::printf("wrote     %s%s\n", run.folder.c_str(),
              run.target.empty() ? " (target.yaml: the default board; --target names yours)" : "");
  return 0;
}

}  // namespace

void print_recording_topics(const RecordingTopics& t, bool raw_images) {
  if (!t.lidar2.empty()) {
    std::printf("topics    lidar %s, lidar2 %s: lidar-lidar\n", t.lidar.c_str(), t.lidar2.c_str());
    return;
  }
  std::printf("topics    lidar %s, left %s (%s)", t.lidar.c_str(), t.left.c_str(), t.left_info.c_str());
  if (!t.right.empty()) std::printf(", right %s (%s)", t.right.c_str(), t.right_info.c_str());
  std::printf("\nimages    %s\n", raw_images ? "raw (K and D apply; images: raw in dataset.yaml)" : "rectified");
}

void add_recording_options(CLI::App* command, RecordingTopics& topics, PairingParams& pairing, bool lidar2) {
  command->add_option("--lidar-topic", topics.lidar, "sensor_msgs/PointCloud2 topic of the lidar");
  if (lidar2)
    command->add_option("--lidar2-topic", topics.lidar2,
                        "PointCloud2 topic of a second lidar: lidar-lidar, no cameras");
  command->add_option("--left-topic", topics.left, "image topic of the left (or only) camera");
  command->add_option("--right-topic", topics.right, "image topic of the right camera");
  command->add_option("--left-info-topic", topics.left_info, "camera_info of the left camera");
  command->add_option("--right-info-topic", topics.right_info, "camera_info of the right camera");
  command->add_option("--tolerance", pairing.tolerance_s,
                      "[s] stamp tolerance of a sweep and its left image (0: half the lidar's median period)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--stereo-tolerance", pairing.stereo_tolerance_s, "[s] left-right stamp tolerance")
      ->check(CLI::NonNegativeNumber);
}

void add_extract_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand("extract", "Write a ROS 1 recording as a dataset folder (DATASET.md)");
  auto run = std::make_shared<ExtractRun>();
  command->add_option("recording", run->recording, "ROS 1 .bag file")->required();
  command->add_option("out_dir", run->folder, "dataset folder to write (new, or empty)")->required();
  command->add_option("--target", run->target, "target.yaml of the board (default: the default board)");
  add_recording_options(command, run->options.topics, run->options.pairing, true);
  command->callback([&runner, run] { runner = [run] { return extract(*run); }; });
}

}  // namespace l2s::cli
