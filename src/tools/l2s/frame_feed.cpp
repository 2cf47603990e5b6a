// FrameFeed (frame_feed.hpp): the frames queued ahead and added in order.
#include "frame_feed.hpp"

#include "calibration_report.hpp"

#include <cstdio>
#include <utility>

namespace l2s::cli {
FrameFeed::FrameFeed(Calibrator& calibrator, const Options& options)
    : calibrator_(calibrator), options_(options), progress_("calibrate", options.frames) {}

FrameFeed::PreparedFrame FrameFeed::prepare(io::Frame frame) const {
  PreparedFrame prepared{std::move(frame), std::nullopt};
  if (!options_.mono && options_.frames_ahead > 0)
    prepared.camera = calibrator_.camera_branch(prepared.frame.left, prepared.frame.right);
  return prepared;
}

void FrameFeed::add_oldest() {
  PreparedFrame prepared = ahead_.front().get();
  ahead_.pop_front();
  io::Frame& frame = prepared.frame;
  const bool accumulated = options_.accumulated && !frame.lidar_stem.empty();
  if (accumulated && frame.lidar_stem == frame.stem) {
    pose_cloud_ = calibrator_.detect_accumulated(frame.lidar);
    pose_points_ = std::move(frame.lidar);
  }
  if (frame.ring_recovery &&
      (frame.ring_recovery->doubtful || frame.ring_recovery->structure == io::ScanStructure::RingFree)) {
    if (doubtful_rings_++ == 0) first_doubt_ = frame.stem + ": " + frame.ring_recovery->summary();
  }
  const FrameReport report =
      accumulated ? (prepared.camera    ? calibrator_.add(pose_cloud_, *prepared.camera, frame.stem)
                     : options_.mono ? calibrator_.add(pose_cloud_, frame.left, frame.stem)
                                     : calibrator_.add(pose_cloud_, frame.left, frame.right, frame.stem))
      : prepared.camera ? calibrator_.add(frame.lidar, *prepared.camera, frame.stem)
      : options_.mono   ? calibrator_.add(frame.lidar, frame.left, frame.stem)
                        : calibrator_.add(frame.lidar, frame.left, frame.right, frame.stem);
  if (options_.verbose) print_frame_failure(report);
  progress_.update(++added_);
  last_frame_ = std::move(frame);
}

io::Frame FrameFeed::finish() {
  while (!ahead_.empty()) add_oldest();
  if (options_.accumulated && !last_frame_.lidar_stem.empty()) last_frame_.lidar = std::move(pose_points_);
  progress_.finish();
  if (doubtful_rings_ > 0)
    std::fprintf(stderr,
                 "l2s: warning: %zu of %zu sweeps have no ring field and a doubtful or no ring structure (first %s)\n",
                 doubtful_rings_, added_, first_doubt_.c_str());
  return std::move(last_frame_);
}

}  // namespace l2s::cli
