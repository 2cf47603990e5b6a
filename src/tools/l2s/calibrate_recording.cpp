// l2s calibrate RECORDING: a ROS 1 recording's paired frames (RecordedFrames)
// streamed into the Calibrator (or, with --lidar2-topic, the
// LidarPairCalibrator) as they are decoded, with no dataset folder
// written. Each sweep is made ready as the dataset reader makes a PCD file's
// (io::settle_rings), so the recording calibrates as the folder `l2s
// extract` writes from it does.

#include "calibrate_options.hpp"
#include "calibration_report.hpp"
#include "commands.hpp"
#include "frame_feed.hpp"

#include <l2s/io/ring_recovery.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/recording/recorded_frames.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <utility>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

void print_recording(const CalibrateOptions& options, const RecordedFrames& frames) {
  std::printf("recording %s\n", options.input.c_str());
  print_recording_topics(frames.topics(), frames.raw_images());
  std::printf("paired    %zu of %zu sweeps (tolerance %.1f ms)%s\n", frames.size(), frames.sweeps(),
              frames.tolerance_s() * 1e3, options.target.empty() ? "; board: the default one (--target names yours)" : "");
  if (options.verbose)
    for (const std::string& dropped : frames.dropped()) std::printf("  left out: %s\n", dropped.c_str());
  else if (!frames.dropped().empty())
    std::printf("  left out: %zu sweep(s) or image(s) (-v lists them), first: %s\n", frames.dropped().size(),
                frames.dropped().front().c_str());
}

/// The frame made ready as the dataset reader makes each sweep
/// (io::settle_rings). An organised cloud keeps its rows here, which the
/// PCD files `l2s extract` writes do not: without a ring field, its rings
/// then come from the rows rather than from the returns.
io::Frame ready_for_calibration(RecordedFrame&& recorded, bool lidar_pair) {
  io::Frame frame = std::move(recorded.frame);
  io::SweptRings rings = io::settle_rings(frame.lidar, recorded.lidar_rows);
  frame.ring_source = rings.source;
  frame.ring_recovery = std::move(rings.recovery);
  if (lidar_pair) {
    io::SweptRings rings2 = io::settle_rings(frame.lidar2, recorded.lidar2_rows);
    frame.lidar2_ring_source = rings2.source;
    frame.lidar2_ring_recovery = std::move(rings2.recovery);
  }
  return frame;
}

/// Where the result goes unless -o says: RECORDING_calibration.yaml beside it.
std::string default_output(const std::string& recording) {
  const fs::path path(recording);
  return (path.parent_path() / (path.stem().string() + "_calibration.yaml")).string();
}

int calibrate_lidar_pair_recording(const CalibrateOptions& options, const RecordedFrames& frames,
                                   const Target& target, const Calibrator::Params& params) {
  LidarPairInput input;
  input.source = options.input;
  input.default_output = default_output(options.input);
  input.target = target;
  input.frames = frames.size();
  input.read_frames = [&frames](std::size_t count, const std::function<void(const io::Frame&)>& visit) {
    std::size_t visited = 0;
    frames.read([&](RecordedFrame&& recorded) {
      visit(ready_for_calibration(std::move(recorded), true));
      return ++visited < count;
    });
  };
  return calibrate_lidar_pair(input, lidar_pair_run(options, params));
}

}  // namespace

int calibrate_recording(const CalibrateOptions& options) {
  const Ros1Bag bag(options.input);
  const RecordedFrames frames(bag, options.topics, options.pairing);
  const Target target = options.target.empty() ? Target{} : io::read_target(options.target);
  const Calibrator::Params params = params_from(options.preset, options.params_file);
  print_recording(options, frames);
  if (frames.lidar_pair()) return calibrate_lidar_pair_recording(options, frames, target, params);
  Calibrator calibrator = frames.mono() ? Calibrator(frames.cameras().left, frames.cameras().images, target, params)
                                        : Calibrator(frames.cameras(), target, params);
  if (frames.mono()) std::printf("mono      left camera alone: board pose from its ArUco markers\n");

  const std::size_t count =
      options.frames > 0 ? std::min<std::size_t>(options.frames, frames.size()) : frames.size();
  FrameFeed feed(calibrator, {count, static_cast<std::size_t>(options.frames_ahead), frames.mono(), false,
                              options.verbose});
  std::size_t pushed = 0;
  frames.read([&](RecordedFrame&& recorded) {
    feed.push([recorded = std::move(recorded)]() mutable { return ready_for_calibration(std::move(recorded), false); });
    return ++pushed < count;
  });
  const io::Frame last_frame = feed.finish();

  CalibrationInput input;
  input.source = options.input;
  input.default_output = default_output(options.input);
  input.left_image = [&frames](const std::string& stem) {
    char* end = nullptr;
    const unsigned long index = std::strtoul(stem.c_str(), &end, 10);
    if (stem.empty() || *end != '\0' || index >= frames.size()) return Image{};
    return frames.load(index).frame.left;
  };
  return report_calibration(options, input, calibrator, last_frame);
}

}  // namespace l2s::cli
