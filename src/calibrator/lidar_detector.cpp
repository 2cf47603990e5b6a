#include "calibrator/lidar_detector.hpp"

#include <chrono>

namespace l2s::detail {
namespace {

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
    window_.push_back(accumulate_ring_free({&sweep}, *params_));
    const auto count = static_cast<int>(window_.size());
    if (count < params_->ring_free_frames) {
      report.failed_stage = "accumulating";
      report.reason = "ring-free sweep " + std::to_string(count) + " of " +
                      std::to_string(params_->ring_free_frames) + " accumulated";
    } else {
      std::vector<const LidarCloud*> window;
      for (const LidarCloud& cloud : window_) window.push_back(&cloud);
      report = run_ring_free_branch(accumulate_ring_free(window, *params_), *target_, *params_, trace);
      window_.clear();
    }
  }
  report.milliseconds = milliseconds_since(start);
  return report;
}

std::optional<BranchReport> LidarDetector::partial_window(LidarInspection* trace) const {
  if (window_.empty()) return std::nullopt;
  std::vector<const LidarCloud*> window;
  for (const LidarCloud& cloud : window_) window.push_back(&cloud);
  return run_ring_free_branch(accumulate_ring_free(window, *params_), *target_, *params_, trace);
}

}  // namespace l2s::detail
