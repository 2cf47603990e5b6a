#pragma once
// The frames a Calibrator keeps for the calibration check (private): evenly
// spread over the frames used, however many there are, and bounded. Every
// stride-th used frame is kept; when more than twice the target are held,
// the stride doubles and the frames off the new stride go.

#include <l2s/scene_observer.hpp>

#include <vector>

namespace l2s::detail {

class CheckFrameKeeper {
 public:
  explicit CheckFrameKeeper(int target) : target_(target) {}

  /// Whether the next used frame is kept: observe it only then.
  bool wants_next() const { return used_ % stride_ == 0; }
  /// Counts the next used frame, keeping `frame` (wants_next() must be true).
  void keep(CheckFrame frame) {
    indices_.push_back(used_++);
    frames_.push_back(std::move(frame));
    if (static_cast<int>(frames_.size()) <= 2 * target_) return;
    stride_ *= 2;
    std::size_t out = 0;
    for (std::size_t i = 0; i < frames_.size(); ++i)
      if (indices_[i] % stride_ == 0) indices_[out] = indices_[i], frames_[out++] = std::move(frames_[i]);
    indices_.resize(out);
    frames_.resize(out);
  }
  /// Counts the next used frame without keeping it.
  void skip() { ++used_; }
  const std::vector<CheckFrame>& frames() const { return frames_; }
  void reset() {
    stride_ = 1;
    used_ = 0;
    indices_.clear();
    frames_.clear();
  }

 private:
  int target_;
  int stride_ = 1;
  int used_ = 0;
  std::vector<int> indices_;  // used-frame index of each kept frame
  std::vector<CheckFrame> frames_;
};

}  // namespace l2s::detail
