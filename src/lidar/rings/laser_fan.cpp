// Fitting the laser fan of a spinning lidar (see laser_fan.hpp): the growth
// from far to near, and the assignment of a whole sweep.
#include "lidar/rings/laser_fan.hpp"

#include "lidar/rings/fan_cleanup.hpp"
#include "lidar/rings/fan_grouping.hpp"
#include "lidar/rings/fan_state.hpp"

#include <algorithm>
#include <limits>

namespace l2s::io::fan {
namespace {

// Returns in order of distance, far first, in chunks narrow in u: a line fitted
// to one chunk predicts the next within a fraction of the laser spacing even
// before the chunks have pinned its offset down.
std::vector<std::vector<std::size_t>> chunks_by_distance(const std::vector<Point>& points) {
  constexpr double kMinWidth = 0.02;  // [1/m]
  constexpr double kGrowth = 0.25;    // a chunk spans u .. 1.25 u beyond kMinWidth
  double u_min = std::numeric_limits<double>::infinity();
  for (const Point& p : points) u_min = std::min(u_min, p.u);
  std::vector<double> ends;
  std::vector<std::vector<std::size_t>> chunks;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (ends.empty() || points[i].u >= ends.back()) {
      const double start = ends.empty() ? u_min : ends.back();
      ends.push_back(start + std::max(kMinWidth, kGrowth * start));
    }
  }
  chunks.resize(ends.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = std::upper_bound(ends.begin(), ends.end(), points[i].u) - ends.begin();
    chunks[std::min<std::size_t>(c, chunks.size() - 1)].push_back(i);
  }
  return chunks;
}

// Gives each candidate to the line that predicts it within its gate and refits
// the lines that took returns. Candidates no line took go to `outliers` when
// the nearest line is sure they are not its own (they may start a new line),
// else to `uncertain`.
void extend_lines(const std::vector<Point>& points, const std::vector<std::size_t>& candidates,
                  std::vector<Fitted>& lines, const OffsetProfile& profile, const FanParams& params,
                  std::vector<std::size_t>& outliers, std::vector<std::size_t>& uncertain) {
  const LineIndex index(plain(lines));
  const OffsetPrior prior(lines, profile, params);
  std::vector<LineSums> added(lines.size());
  for (std::size_t i : candidates) {
    const Decision d = classify(lines, index.nearest(points[i]), points[i], params);
    if (d.verdict == Verdict::Accept) {
      added[d.line].add(points[i]);
      lines[d.line].members.push_back(i);
    } else if (d.verdict == Verdict::Outlier)
      outliers.push_back(i);
    else
      uncertain.push_back(i);
  }
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (added[k].n == 0) continue;
    lines[k].sums.add(added[k]);
    lines[k].line = fit(lines[k].sums, prior, profile, params);
  }
  sort_by_intercept(lines);
}

}  // namespace

Fan fit_fan(const std::vector<Point>& all, const FanParams& params) {
  Fan fan;
  std::vector<Point> points;
  const std::size_t stride =
      std::max<std::size_t>(1, (all.size() + params.max_points - 1) / params.max_points);
  for (std::size_t i = 0; i < all.size(); i += stride) points.push_back(all[i]);
  if (points.empty()) return fan;
  fan.profile = OffsetProfile::estimate(points, params.profile);

  std::vector<Fitted> lines;
  std::vector<std::size_t> pending;  // returns no line took yet, too few for a line of their own
  for (const auto& chunk : chunks_by_distance(points)) {
    ++fan.chunks;
    std::vector<std::size_t> candidates = pending, outliers, uncertain;
    candidates.insert(candidates.end(), chunk.begin(), chunk.end());
    extend_lines(points, candidates, lines, fan.profile, params, outliers, uncertain);
    split_wide_lines(points, lines, fan.profile, params);
    pending = add_new_lines(points, outliers, lines, fan.profile, params, params.new_line_range);
    pending.insert(pending.end(), uncertain.begin(), uncertain.end());
  }
  for (int round = 0; round < 2; ++round) {
    refit_all(lines, fan.profile, params);
    while (merge_lines(lines, fan.profile, params) > 0) {
    }
    dissolve_strays(lines);
    dissolve_crossing(lines, params);
    reassign(points, lines, fan.profile, params);
  }
  fan.lines = plain(lines);
  return fan;
}

std::vector<int> assign_all(const std::vector<Point>& points, Fan& fan, const FanParams& params) {
  std::vector<int> labels(points.size(), -1);
  if (fan.lines.empty()) return labels;
  std::vector<Fitted> lines;
  for (const Line& l : fan.lines) lines.push_back({l, {}, {}});
  // Returns no line explains although the lines are sure of themselves there
  // may be a laser too sparse to show in the fit's sample: if they cluster,
  // it gets a line and every return is assigned again.
  std::vector<std::size_t> outliers;
  const LineIndex index(fan.lines, true);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Match m = index.nearest(points[i]);
    labels[i] = m.line;
    // Most returns lie within the gate of their nearest line: no need to ask others.
    const bool near = m.residual * m.residual <=
                      params.gate * params.gate * fan.lines[m.line].variance(points[i].u);
    if (!near && classify(lines, m, points[i], params).verdict == Verdict::Outlier)
      outliers.push_back(i);
    else
      lines[m.line].sums.add(points[i]);
  }
  const std::size_t before = lines.size();
  // A laser the sample missed has returns across the scene, not only at the
  // short range where noisy returns of dense lasers run into each other.
  add_new_lines(points, outliers, lines, fan.profile, params, 2.0 * params.new_line_range);
  if (lines.size() == before) return labels;
  while (merge_lines(lines, fan.profile, params) > 0) {
  }
  dissolve_crossing(lines, params);
  fan.lines = plain(lines);
  const LineIndex updated(fan.lines, true);
  for (std::size_t i = 0; i < points.size(); ++i) labels[i] = updated.nearest(points[i]).line;
  return labels;
}

}  // namespace l2s::io::fan
