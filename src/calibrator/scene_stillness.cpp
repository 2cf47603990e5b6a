#include "calibrator/scene_stillness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace l2s::detail {
namespace {

// Half a degree: about two Livox beam footprints, so a sweep of 20,000
// returns over a 70 deg field of view meets cells earlier sweeps have seen,
// while a board a few metres away still covers hundreds of them.
constexpr double kCellRad = 0.5 * M_PI / 180.0;
// A return agrees with its cells within 4 sigma of a solid-state lidar's
// range noise (2 cm) plus 1 % of the range for a surface seen at a slant.
constexpr double kTolerance = 0.08;
constexpr double kRelativeTolerance = 0.01;
// Motion: this many changed returns, and this share of those compared.
// Measured on Mid-360- and Avia-like lidars in random scenes (the whole
// sweep within 10 m): a static scene changes 0-7 returns of 400-5,000
// compared (at most 0.5 %), the first frame of a board on its way 68 of
// 4,400 (1.5 %) and the next ones 120-15,000.
constexpr int kMinChanged = 30;
constexpr double kMinChangedShare = 0.01;

// Cells are keyed by azimuth index * kRowStride + elevation index (both
// within +-360 cells of half a degree).
constexpr std::int64_t kRowStride = 4096;

std::int64_t cell_of(const Eigen::Vector3d& p) {
  const double azimuth = std::atan2(p.y(), p.x());
  const double elevation = std::atan2(p.z(), std::hypot(p.x(), p.y()));
  const auto a = static_cast<std::int64_t>(std::floor(azimuth / kCellRad));
  const auto e = static_cast<std::int64_t>(std::floor(elevation / kCellRad));
  return a * kRowStride + e;
}

}  // namespace

SceneStillness::Comparison SceneStillness::compare(const LidarCloud& sweep) const {
  Comparison result;
  if (cells_.empty()) return result;
  for (const auto& p : sweep.points) {
    if (!p.allFinite()) continue;
    const std::int64_t key = cell_of(p);
    if (!cells_.count(key)) continue;
    // The span of the cell and its eight neighbours: a surface seen at a
    // grazing angle (the floor a few metres away) changes its range by tens
    // of centimetres within one cell, and its neighbours hold the ranges
    // beyond either side of it.
    float nearest = std::numeric_limits<float>::max(), farthest = 0.0f;
    for (std::int64_t da = -1; da <= 1; ++da)
      for (std::int64_t de = -1; de <= 1; ++de) {
        const auto cell = cells_.find(key + da * kRowStride + de);
        if (cell == cells_.end()) continue;
        nearest = std::min(nearest, cell->second.nearest);
        farthest = std::max(farthest, cell->second.farthest);
      }
    const double range = p.norm();
    const double tolerance = kTolerance + kRelativeTolerance * range;
    ++result.compared;
    if (range < nearest - tolerance || range > farthest + tolerance) ++result.changed;
  }
  result.moved = result.changed >= kMinChanged && result.changed >= kMinChangedShare * result.compared;
  return result;
}

void SceneStillness::add(const LidarCloud& sweep) {
  for (const auto& p : sweep.points) {
    if (!p.allFinite()) continue;
    const auto range = static_cast<float>(p.norm());
    const auto [cell, fresh] = cells_.try_emplace(cell_of(p), Span{range, range});
    if (!fresh) {
      cell->second.nearest = std::min(cell->second.nearest, range);
      cell->second.farthest = std::max(cell->second.farthest, range);
    }
  }
}

}  // namespace l2s::detail
