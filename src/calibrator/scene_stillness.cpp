#include "calibrator/scene_stillness.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

// Half a degree: about two Livox beam footprints, so a sweep of 20,000
// returns over a 70 deg field of view meets cells earlier sweeps have seen,
// while a board a few metres away still covers hundreds of them.
constexpr double kCellRad = 0.5 * M_PI / 180.0;
// A return agrees with a cell within 3 sigma of a solid-state lidar's range
// noise (2 cm) plus 1 % of the range for the cell's own depth spread on a
// surface seen at a slant.
constexpr double kTolerance = 0.06;
constexpr double kRelativeTolerance = 0.01;
// Motion: this many changed returns, and this share of those compared. The
// returns are the pass-through's, around the board, so the board is a large
// part of them: a board moved on (the frames between two poses) changed 65-75
// % of an Avia's returns, while a static scene changes 1-2 % (returns on the
// floor at a grazing angle, whose range spans more within a cell than the
// window has seen yet). A board shifted by a tenth of its width across its
// plane changes a fifth of its own.
constexpr int kMinChanged = 100;
constexpr double kMinChangedShare = 0.05;

std::int64_t cell_of(const Eigen::Vector3d& p) {
  const double azimuth = std::atan2(p.y(), p.x());
  const double elevation = std::atan2(p.z(), std::hypot(p.x(), p.y()));
  const auto a = static_cast<std::int64_t>(std::floor(azimuth / kCellRad));
  const auto e = static_cast<std::int64_t>(std::floor(elevation / kCellRad));
  return a * 4096 + e;
}

}  // namespace

SceneStillness::Comparison SceneStillness::compare(const LidarCloud& sweep) const {
  Comparison result;
  if (cells_.empty()) return result;
  for (const auto& p : sweep.points) {
    if (!p.allFinite()) continue;
    const auto cell = cells_.find(cell_of(p));
    if (cell == cells_.end()) continue;
    const double range = p.norm();
    const double tolerance = kTolerance + kRelativeTolerance * range;
    ++result.compared;
    if (range < cell->second.nearest - tolerance || range > cell->second.farthest + tolerance) ++result.changed;
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
