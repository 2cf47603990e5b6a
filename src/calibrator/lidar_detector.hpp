#pragma once
// One lidar's board detector over a stream of sweeps (private): a ring lidar
// is detected sweep by sweep; a ring-free one (non-repetitive scan) is
// accumulated over params.ring_free_frames sweeps of the static board and
// detected once per window (a window without the board grows, up to twice
// that, before it starts afresh). A window holds one pose of the board: when
// a sweep shows the scene moved (SceneStillness), the window is closed,
// detected with what it holds, and a new one starts with that sweep. Shared by every facade with a lidar in it (the
// stereo Calibrator, the LidarPairCalibrator), so each lidar of a rig keeps
// its own window.

#include "calibrator/branches.hpp"
#include "calibrator/scene_stillness.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace l2s::detail {

class LidarDetector {
 public:
  /// `target` and `params` must outlive the detector (the facade owns them).
  LidarDetector(const Target& target, const Calibrator::Params& params) : target_(&target), params_(&params) {}

  /// The lidar branch of one sweep: at once for a ring lidar; for a
  /// ring-free one (`ring_free`, from is_ring_free), when ring_free_frames
  /// sweeps are together; until then the report's stage is "accumulating".
  /// `trace` receives the detection's stages, when one ran. Timed.
  BranchReport detect(const LidarCloud& sweep, bool ring_free, LidarInspection* trace = nullptr);

  /// A ring-free window still short of ring_free_frames, detected as it
  /// stands (its sweeps are data too); nothing is changed, more may follow.
  /// `trace` as for detect().
  std::optional<BranchReport> partial_window(LidarInspection* trace = nullptr) const;

  /// Ring-free sweeps waiting in the window.
  int window_size() const { return static_cast<int>(window_.size()); }

  /// What the last detect() did when its sweep showed the scene moved: a new
  /// window started with that sweep, and the old one (which belongs with
  /// the sweep before) was detected, if it held enough sweeps.
  struct WindowClose {
    bool restarted = false;
    std::optional<BranchReport> closed;
  };
  /// Hands that over once (later calls give nothing until the next move).
  WindowClose take_window_close() {
    WindowClose close{restarted_, std::move(closed_)};
    restarted_ = false;
    closed_.reset();
    return close;
  }

  /// Forgets the window being accumulated.
  void reset() {
    window_.clear();
    stillness_.clear();
    closed_.reset();
    restarted_ = false;
  }

  /// Puts a window's detection on the report of the frame it belongs with
  /// (the last sweep of its pose), whose time it adds to.
  static void place_window(BranchReport detection, const std::string& note, BranchReport& frame) {
    detection.milliseconds += frame.milliseconds;
    detection.note = note;
    frame = std::move(detection);
  }

 private:
  BranchReport detect_window(LidarInspection* trace) const;  // the window's sweeps as one cloud

  const Target* target_;
  const Calibrator::Params* params_;
  std::vector<LidarCloud> window_;  // ring-free sweeps waiting for a detection (pass-through applied)
  SceneStillness stillness_;        // the scene since the last move, to tell the next one
  std::optional<BranchReport> closed_;
  bool restarted_ = false;
};

}  // namespace l2s::detail
