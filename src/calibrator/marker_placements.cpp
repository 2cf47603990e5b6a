// A mono board's marker placements over a calibration's frames (marker_placements.hpp).

#include "calibrator/marker_placements.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace l2s::detail {
namespace {

constexpr std::size_t kMinFrames = 3;   // fewer frames say nothing steady
constexpr double kMinOffset = 0.0015;   // [m] below this a print is as good as its layout

double median(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + static_cast<long>(mid)));
}

/// 1-sigma of the median of `values` (1.2533 sigma / sqrt(n), sigma from the MAD).
double median_error(const std::vector<double>& values, double centre) {
  std::vector<double> deviations;
  for (double v : values) deviations.push_back(std::abs(v - centre));
  return 1.2533 * 1.4826 * median(deviations) / std::sqrt(static_cast<double>(values.size()));
}

}  // namespace

MarkerPlacements summarise_marker_placements(const std::vector<FrameReport>& frames) {
  std::map<int, std::vector<const MonoBoardDetector::MarkerPlacement*>> by_marker;
  for (const FrameReport& frame : frames)
    for (const auto& placement : frame.camera.marker_placements)
      if (placement.placed) by_marker[placement.id].push_back(&placement);
  MarkerPlacements summary;
  for (const auto& [id, placements] : by_marker) {
    if (placements.size() < kMinFrames) continue;
    std::vector<double> x, y, turn, rms;
    std::size_t left_out = 0;
    for (const auto* p : placements) {
      x.push_back(p->offset.x()), y.push_back(p->offset.y()), turn.push_back(p->rotation_deg), rms.push_back(p->rms_px);
      left_out += p->left_out;
    }
    MonoBoardDetector::MarkerPlacement marker;
    marker.id = id;
    marker.placed = true;
    marker.offset = Eigen::Vector2d(median(x), median(y));
    marker.rotation_deg = median(turn);
    marker.rms_px = median(rms);
    marker.left_out = 2 * left_out > placements.size();
    summary.markers.push_back(marker);
    const double error = std::hypot(median_error(x, marker.offset.x()), median_error(y, marker.offset.y()));
    if (marker.offset.norm() <= std::max(kMinOffset, 3.0 * error)) continue;
    char note[300];
    std::snprintf(note, sizeof note,
                  "marker %d lies %.1f mm off its place in target.yaml (median of %zu frames: x %+.1f mm, y %+.1f mm, "
                  "turned %+.2f deg%s): where it is glued, measured on the board, belongs in target.yaml's "
                  "markers: centres",
                  id, marker.offset.norm() * 1e3, placements.size(), marker.offset.x() * 1e3, marker.offset.y() * 1e3,
                  marker.rotation_deg, marker.left_out ? "; left out of the pose where the others agreed" : "");
    summary.notes.push_back(note);
  }
  return summary;
}

}  // namespace l2s::detail
