#pragma once
// Frames handed to the Calibrator in order, whatever they are read from (a
// dataset folder, a recording), with a stereo frame's camera branch run on
// worker threads a few frames ahead.

#include "progress_bar.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/io/dataset.hpp>

#include <algorithm>
#include <cstddef>
#include <deque>
#include <future>
#include <optional>
#include <string>

namespace l2s::cli {

/// Frames are read, and a stereo frame's camera branch run, `frames_ahead`
/// frames ahead on worker threads, while the calling thread runs each
/// frame's lidar branch and accumulates the frames in order
/// (Calibrator::camera_branch() reads only what the calibrator was built
/// with). The camera branch of one frame keeps about one core busy (its
/// stereo matching parallelises little), so on two cores two frames in
/// flight take a third off the time per frame (setting 1, 30 frames, runs
/// interleaved with --frames-ahead 0: 7.8 -> 5.1 s). The result is the one
/// add(lidar, left, right) gives frame by frame; a frame that cannot be read
/// throws in order. 0 frames ahead: one frame at a time, its two branches
/// side by side (Calibrator::add).
class FrameFeed {
 public:
  struct Options {
    std::size_t frames = 0;        ///< how many will be pushed (for the progress bar)
    std::size_t frames_ahead = 2;
    bool mono = false;             ///< left images alone: no camera branch ahead
    bool accumulated = false;      ///< `lidar: accumulated`: a pose's cloud comes with its first frame
    bool verbose = false;          ///< print why each frame was not used
  };

  FrameFeed(Calibrator& calibrator, const Options& options);
  /// Workers still running when an exception leaves finish before the
  /// calibrator they use is gone: the futures' destructors wait.
  ~FrameFeed() = default;
  FrameFeed(const FrameFeed&) = delete;
  FrameFeed& operator=(const FrameFeed&) = delete;

  /// Queues the frame `read()` gives (run on a worker thread when frames
  /// run ahead); adds the oldest queued frame once more than `frames_ahead`
  /// wait.
  template <class Read>
  void push(Read read) {
    const auto policy = options_.frames_ahead > 0 ? std::launch::async : std::launch::deferred;
    ahead_.push_back(std::async(policy, [this, read = std::move(read)]() mutable { return prepare(read()); }));
    while (ahead_.size() > std::max<std::size_t>(options_.frames_ahead, 1)) add_oldest();
  }

  /// Adds the frames still queued; returns the last frame added (the
  /// overlay's fallback). Warns once about sweeps whose rings had to be
  /// recovered and look doubtful.
  io::Frame finish();

 private:
  /// One frame read and, for a stereo frame, its camera branch run.
  struct PreparedFrame {
    io::Frame frame;
    std::optional<BranchReport> camera;
  };

  PreparedFrame prepare(io::Frame frame) const;
  void add_oldest();

  Calibrator& calibrator_;
  Options options_;
  ProgressBar progress_;
  std::deque<std::future<PreparedFrame>> ahead_;
  std::size_t added_ = 0;
  io::Frame last_frame_;
  std::size_t doubtful_rings_ = 0;
  std::string first_doubt_;
  AccumulatedLidar pose_cloud_;  // `lidar: accumulated`: the cloud of the pose being added, detected once
  LidarCloud pose_points_;
};

}  // namespace l2s::cli
