#include "calibrator/lidar_detector.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace l2s::detail {
namespace {

/// A window whose board was not found keeps its sweeps and is detected
/// again every ring_free_frames / 2 more, up to this many times
/// ring_free_frames; then it starts afresh. A sparse scan needs more sweeps
/// than the default window to show the holes: a Mid-360 3.5 m from the
/// board puts about 150 returns a sweep on it, and a window of 15 sweeps
/// leaves the rims of its holes too thinly drawn to fit, where twice as
/// many sweeps draw them.
constexpr int kLongestWindow = 2;

/// A window closed at a move is detected when it holds at least this many
/// sweeps: a single one lies between two moves (the board on its way).
constexpr int kMinClosedWindow = 2;

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

BranchReport LidarDetector::detect(const LidarCloud& sweep, bool ring_free, LidarInspection* trace) {
  const auto start = std::chrono::steady_clock::now();
  BranchReport report;
  if (!ring_free) {
    report = run_lidar_branch(sweep, *target_, *params_, trace);
  } else {
    LidarCloud kept = accumulate_ring_free({&sweep}, *params_);
    closed_.reset();
    restarted_ = stillness_.compare(kept).moved;
    if (restarted_) {
      if (static_cast<int>(window_.size()) >= kMinClosedWindow) {
        closed_ = detect_window(trace);
        if (!closed_->found)
          closed_->reason = "not found in a window of " + std::to_string(window_.size()) +
                            " sweeps closed at a move of the scene (" + closed_->failed_stage + ": " +
                            closed_->reason + ")";
      }
      window_.clear();
      stillness_.clear();
    }
    stillness_.add(kept);
    window_.push_back(std::move(kept));
    const auto count = static_cast<int>(window_.size());
    const int first = params_->ring_free_frames;
    const int again = std::max(1, first / 2);
    const int longest = kLongestWindow * first;
    const bool due = count >= first && ((count - first) % again == 0 || count >= longest);
    if (!due) {
      report.failed_stage = "accumulating";
      report.reason = "ring-free sweep " + std::to_string(count) + " of " + std::to_string(first) + " accumulated";
      if (count > first) report.reason += " (a window without the board grows, up to " + std::to_string(longest) + ")";
    } else {
      report = detect_window(trace);
      if (report.found || count >= longest) {
        window_.clear();
      } else {
        report.reason = "not found in a window of " + std::to_string(count) + " sweeps (" + report.failed_stage +
                        ": " + report.reason + "); the window grows, up to " + std::to_string(longest);
        report.failed_stage = "accumulating";
      }
    }
  }
  report.milliseconds = milliseconds_since(start);
  return report;
}

std::optional<BranchReport> LidarDetector::partial_window(LidarInspection* trace) const {
  if (window_.empty()) return std::nullopt;
  return detect_window(trace);
}

BranchReport LidarDetector::detect_window(LidarInspection* trace) const {
  std::vector<const LidarCloud*> window;
  for (const LidarCloud& cloud : window_) window.push_back(&cloud);
  LidarInspection own_trace;
  LidarInspection& stages = trace ? *trace : own_trace;
  BranchReport report = run_ring_free_branch(accumulate_ring_free(window, *params_), *target_, *params_, &stages);
  // A board whose points lie too far apart for its holes needs a longer
  // still stand, which the user can give: say how long in sweeps.
  if (!report.found && stages.occupancy && stages.occupancy->sparse_factor > 1.0) {
    const auto sweeps = static_cast<int>(window_.size());
    const int needed = static_cast<int>(std::ceil(stages.occupancy->sparse_factor * sweeps));
    report.reason += "; the window held " + std::to_string(sweeps) + " sweep(s) of the static board: hold it still for " +
                     std::to_string(needed) + " sweeps or more";
  }
  return report;
}

}  // namespace l2s::detail
