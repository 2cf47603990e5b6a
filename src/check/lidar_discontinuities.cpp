// Whole-sweep depth discontinuities for the calibration check (after
// Levinson and Thrun 2013, "Automatic online calibration of cameras and
// lasers": the near side of range jumps along each scan line).

#include "check/lidar_discontinuities.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <unordered_map>

namespace l2s::detail {
namespace {

struct Return {
  double azimuth;    // [rad] atan2(y, x)
  double elevation;  // [rad]
  double range;      // [m]
};

Eigen::Vector3d point_at(double azimuth, double elevation, double range) {
  const double c = std::cos(elevation);
  return range * Eigen::Vector3d(c * std::cos(azimuth), c * std::sin(azimuth), std::sin(elevation));
}

/// Median spacing of consecutive azimuths (sorted); 0 with fewer than two.
double median_step(const std::vector<Return>& ring) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < ring.size(); ++i)
    if (ring[i].azimuth > ring[i - 1].azimuth) steps.push_back(ring[i].azimuth - ring[i - 1].azimuth);
  if (steps.empty()) return 0.0;
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

/// The edges of one ring, sorted by azimuth.
void ring_edges(const std::vector<Return>& ring, const JumpRule& rule, std::vector<Eigen::Vector3d>& out) {
  const std::size_t n = ring.size();
  const double step = median_step(ring);
  if (n < 3 || !(step > 0.0)) return;
  // A full turn wraps around; a partial one (a limited field of view) has open ends.
  const bool closed = ring.front().azimuth + 2.0 * M_PI - ring.back().azimuth <= rule.gap_factor * step;
  for (std::size_t i = 0; i < n; ++i) {
    const Return& a = ring[i];
    for (const int side : {-1, 1}) {
      const bool at_end = (side < 0 && i == 0) || (side > 0 && i + 1 == n);
      if (at_end && !closed) continue;
      const Return& b = ring[(i + n + side) % n];
      double gap = side * (b.azimuth - a.azimuth);
      if (gap < 0.0) gap += 2.0 * M_PI;
      if (gap > rule.gap_factor * step)  // no return between: the far side is open (sky, out of range)
        out.push_back(point_at(a.azimuth + side * 0.5 * step, a.elevation, a.range));
      else if (rule.jumps(a.range, b.range))
        out.push_back(point_at(a.azimuth + side * 0.5 * gap, a.elevation, a.range));
    }
  }
}

Return to_return(const Eigen::Vector3d& p) {
  const double horizontal = std::hypot(p.x(), p.y());
  return {std::atan2(p.y(), p.x()), std::atan2(p.z(), horizontal), p.norm()};
}

}  // namespace

std::vector<Eigen::Vector3d> ring_discontinuities(const LidarCloud& cloud, const JumpRule& rule) {
  std::vector<std::vector<Return>> rings;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite() || p.norm() < rule.min_range) continue;
    const std::size_t ring = cloud.ring[i];
    if (ring >= rings.size()) rings.resize(ring + 1);
    rings[ring].push_back(to_return(p));
  }
  std::vector<Eigen::Vector3d> edges;
  for (auto& ring : rings) {
    std::sort(ring.begin(), ring.end(), [](const Return& a, const Return& b) { return a.azimuth < b.azimuth; });
    ring_edges(ring, rule, edges);
  }
  return edges;
}

std::vector<Eigen::Vector3d> grid_discontinuities(const LidarCloud& cloud, const JumpRule& rule, double step) {
  // Nearest return per cell; keys pack (column, row) into one integer.
  // (Unsigned: a negative column shifted left is undefined behaviour.)
  const auto key = [](std::int64_t column, std::int64_t row) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(column) << 32) ^
                                     (static_cast<std::uint64_t>(row) & 0xffffffffULL));
  };
  std::unordered_map<std::int64_t, Return> cells;
  for (const Eigen::Vector3d& p : cloud.points) {
    if (!p.allFinite() || p.norm() < rule.min_range) continue;
    const Return r = to_return(p);
    const std::int64_t k = key(std::llround(r.azimuth / step), std::llround(r.elevation / step));
    const auto [it, added] = cells.emplace(k, r);
    if (!added && r.range < it->second.range) it->second = r;
  }
  std::vector<Eigen::Vector3d> edges;
  for (const auto& [k, a] : cells) {
    const std::int64_t column = std::llround(a.azimuth / step), row = std::llround(a.elevation / step);
    for (const auto& [dc, dr] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
      const auto it = cells.find(key(column + dc, row + dr));
      if (it == cells.end() || !rule.jumps(a.range, it->second.range)) continue;
      const Return& b = it->second;
      edges.push_back(point_at(0.5 * (a.azimuth + b.azimuth), 0.5 * (a.elevation + b.elevation), a.range));
    }
  }
  // Hash order is not portable: sort for the same output everywhere.
  std::sort(edges.begin(), edges.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
  });
  return edges;
}

}  // namespace l2s::detail
