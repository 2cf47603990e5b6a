#pragma once
// The frames a Calibrator keeps for the calibration check (private), from two
// streams, each evenly spread over its own frames and bounded:
//  - board frames: both sensors found the board (the board's evidence and the
//    scene's);
//  - scene frames: the others, whose depth edges and stereo depth still test
//    the transform. Kept only while there are fewer board frames than the
//    target: a ring-free lidar finds the board once per accumulated window,
//    so a 30-frame calibration had one board frame to check against, and one
//    frame's evidence can prefer a wrong transform (a board alone is
//    symmetric under a half turn: one frame's edges can fit a result turned
//    180 deg as well; eight frames of the scene around it tell them apart).
// In each stream every stride-th frame is kept; when more than twice the
// target are held, the stride doubles and the frames off the new stride go.

#include <l2s/scene_observer.hpp>

#include <algorithm>
#include <vector>

namespace l2s::detail {

class CheckFrameKeeper {
 public:
  enum class Kind { Board, Scene };

  explicit CheckFrameKeeper(int target) : target_(target) {}

  /// Whether the next frame of `kind` is kept: observe it only then.
  bool wants_next(Kind kind) const {
    if (kind == Kind::Scene && board_frames() >= target_) return false;
    return stream(kind).used % stream(kind).stride == 0;
  }
  /// Counts the next frame of `kind`, keeping `frame` (wants_next(kind) must be true).
  void keep(Kind kind, CheckFrame frame) {
    Stream& s = stream(kind);
    held_.push_back({kind, s.used++});
    frames_.push_back(std::move(frame));
    if (kind == Kind::Board && board_frames() >= target_) drop(Kind::Scene, 0);
    if (count(kind) > 2 * target_) drop(kind, s.stride *= 2);
  }
  /// Counts the next frame of `kind` without keeping it.
  void skip(Kind kind) { ++stream(kind).used; }
  /// The kept frames, in the order they came.
  const std::vector<CheckFrame>& frames() const { return frames_; }
  int board_frames() const { return count(Kind::Board); }
  void reset() {
    boards_ = scenes_ = Stream{};
    held_.clear();
    frames_.clear();
  }

 private:
  struct Stream {
    int stride = 1;
    int used = 0;
  };
  struct Held {
    Kind kind;
    int index;  // within its stream
  };

  Stream& stream(Kind kind) { return kind == Kind::Board ? boards_ : scenes_; }
  const Stream& stream(Kind kind) const { return kind == Kind::Board ? boards_ : scenes_; }
  int count(Kind kind) const {
    return static_cast<int>(std::count_if(held_.begin(), held_.end(), [&](const Held& h) { return h.kind == kind; }));
  }
  /// Drops the frames of `kind` off `stride` (every one of them for stride 0).
  void drop(Kind kind, int stride) {
    std::size_t out = 0;
    for (std::size_t i = 0; i < held_.size(); ++i) {
      const bool goes = held_[i].kind == kind && (stride == 0 || held_[i].index % stride != 0);
      if (goes) continue;
      if (out != i) held_[out] = held_[i], frames_[out] = std::move(frames_[i]);
      ++out;
    }
    held_.resize(out);
    frames_.resize(out);
  }

  int target_;
  Stream boards_, scenes_;
  std::vector<Held> held_;          // parallel to frames_
  std::vector<CheckFrame> frames_;
};

}  // namespace l2s::detail
