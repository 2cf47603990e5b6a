// Grouping returns into lasers (see fan_grouping.hpp).
#include "lidar/rings/fan_grouping.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::io::fan {

namespace {

// Appends the run sorted[begin, end) as one group, or as several where lasers
// touch (noisy returns close the gap between lasers 0.33 deg apart): the run's
// density (a histogram of bins a fifth of the minimum gap, smoothed) is cut at
// each valley below kValley of the lower of the two peaks around it, where
// the peaks lie at least the minimum gap apart and the valley is significant.
void split_run(const Run& sorted, std::size_t begin, std::size_t end, const FanParams& params,
               std::vector<std::vector<std::size_t>>& groups) {
  constexpr double kValley = 0.5;
  constexpr double kSignificance = 1.5;  // valley depth in standard deviations of the peak count
  const auto emit = [&](std::size_t from, std::size_t to) {
    if (to - from < params.min_points) return;
    std::vector<std::size_t> group;
    for (std::size_t i = from; i < to; ++i) group.push_back(sorted[i].second);
    groups.push_back(group);
  };
  const double low = sorted[begin].first,
               min_gap = params.min_gap * v_per_radian(sorted[(begin + end) / 2].first);
  if (sorted[end - 1].first - low < min_gap) return emit(begin, end);
  const double bin = 0.2 * min_gap;
  std::vector<double> density(static_cast<std::size_t>((sorted[end - 1].first - low) / bin) + 3,
                              0.0);
  for (std::size_t i = begin; i < end; ++i)
    density[static_cast<std::size_t>((sorted[i].first - low) / bin) + 1] += 1.0;
  for (int pass = 0; pass < 2; ++pass) {  // [1 2 1] / 4 twice: a kernel of ~1 bin sigma
    std::vector<double> smooth(density.size(), 0.0);
    for (std::size_t b = 1; b + 1 < density.size(); ++b)
      smooth[b] = 0.25 * density[b - 1] + 0.5 * density[b] + 0.25 * density[b + 1];
    density.swap(smooth);
  }
  // Peaks closer than the minimum gap are one peak (the higher one).
  std::vector<std::size_t> peaks;
  for (std::size_t b = 1; b + 1 < density.size(); ++b) {
    if (density[b] < density[b - 1] || density[b] < density[b + 1] || density[b] <= 0.0) continue;
    if (!peaks.empty() && (b - peaks.back()) * bin < min_gap) {
      if (density[b] > density[peaks.back()]) peaks.back() = b;
      continue;
    }
    peaks.push_back(b);
  }
  std::size_t from = begin;
  for (std::size_t k = 0; k + 1 < peaks.size(); ++k) {
    std::size_t valley = peaks[k];
    for (std::size_t b = peaks[k]; b <= peaks[k + 1]; ++b)
      if (density[b] < density[valley]) valley = b;
    const double lower = std::min(density[peaks[k]], density[peaks[k + 1]]);
    // Deep, and deeper than the counting noise of the peak (a few returns per
    // bin make bumps in one noisy laser that are no second laser).
    if (density[valley] >= kValley * lower ||
        lower - density[valley] < kSignificance * std::sqrt(lower))
      continue;
    const double cut = low + (static_cast<double>(valley) - 0.5) * bin;
    std::size_t to = from;
    while (to < end && sorted[to].first < cut) ++to;
    emit(from, to);
    from = to;
  }
  emit(from, end);
}

}  // namespace

std::vector<std::vector<std::size_t>> groups_of(const Run& sorted, const FanParams& params) {
  std::vector<std::vector<std::size_t>> groups;
  std::size_t begin = 0;
  for (std::size_t s = 1; s <= sorted.size(); ++s) {
    if (s < sorted.size() &&
        sorted[s].first - sorted[s - 1].first <= params.min_gap * v_per_radian(sorted[s].first))
      continue;
    split_run(sorted, begin, s, params, groups);
    begin = s;
  }
  return groups;
}

// Offsets change smoothly across the fan, so a laser not seen yet shares its
// neighbours' offset better than the profile's average: returns of one laser
// at different distances then line up.
std::vector<std::vector<std::size_t>> cluster(const std::vector<Point>& points,
                                              const std::vector<std::size_t>& members,
                                              const std::vector<Line>& lines,
                                              const OffsetProfile& profile,
                                              const FanParams& params) {
  const LineIndex index(lines);
  Run sorted;
  for (std::size_t i : members) {
    const Match m = index.nearest(points[i]);
    sorted.emplace_back(m.line < 0 ? profile.intercept(points[i]) : lines[m.line].t + m.residual,
                        i);
  }
  std::sort(sorted.begin(), sorted.end());
  return groups_of(sorted, params);
}

// Only returns beyond min_range may start a line: nearer ones are where the
// lines of densely packed lasers (HDL-64E) run into each other.
std::vector<std::size_t> add_new_lines(const std::vector<Point>& points,
                                       const std::vector<std::size_t>& candidates,
                                       std::vector<Fitted>& lines, const OffsetProfile& profile,
                                       const FanParams& params, double min_range) {
  constexpr double kShareOfMedian = 0.01;
  std::vector<std::size_t> far;
  for (std::size_t i : candidates)
    if (points[i].u * min_range <= 1.0) far.push_back(i);
  std::vector<double> counts;
  for (const Fitted& f : lines) counts.push_back(f.sums.n);
  std::size_t needed = params.min_points;
  if (!counts.empty()) {
    std::nth_element(counts.begin(), counts.begin() + counts.size() / 2, counts.end());
    needed = std::max(needed, static_cast<std::size_t>(kShareOfMedian * counts[counts.size() / 2]));
  }
  const OffsetPrior prior(lines, profile, params);
  std::vector<bool> used(points.size(), false);
  for (const auto& group : cluster(points, far, plain(lines), profile, params)) {
    if (group.size() < needed) continue;
    LineSums sums;
    for (std::size_t i : group) sums.add(points[i]), used[i] = true;
    lines.push_back({fit(sums, prior, profile, params), sums, group});
  }
  sort_by_intercept(lines);
  std::vector<std::size_t> rest;
  for (std::size_t i : candidates)
    if (!used[i]) rest.push_back(i);
  return rest;
}

// A line whose residuals spread far wider than a laser's (kWide times the
// sensor's noise) took the returns of a neighbouring laser as well, and each
// return it takes widens its gate further: its returns beyond new_line_range
// are grouped again by their intercepts under its own offset, and each group
// becomes a line (nearer returns, where a small error in the offset moves the
// intercept a lot, are left for the final assignment). Returns the number of
// lines split.
std::size_t split_wide_lines(const std::vector<Point>& points, std::vector<Fitted>& lines,
                             const OffsetProfile& profile, const FanParams& params) {
  constexpr double kWide = 2.5;
  const double noise = typical_noise(lines, params);
  const OffsetPrior prior(lines, profile, params);
  std::vector<Fitted> result;
  std::size_t splits = 0;
  for (Fitted& f : lines) {
    if (f.line.scale <= kWide * noise * v_per_radian(f.line.t) ||
        f.members.size() < 2 * params.min_points) {
      result.push_back(std::move(f));
      continue;
    }
    Run sorted;
    for (std::size_t i : f.members)
      if (points[i].u * params.new_line_range <= 1.0)
        sorted.emplace_back(points[i].v - f.line.h * points[i].u, i);
    std::sort(sorted.begin(), sorted.end());
    const auto groups = groups_of(sorted, params);
    if (groups.size() < 2) {
      result.push_back(std::move(f));
      continue;
    }
    ++splits;
    for (const auto& group : groups) {
      LineSums sums;
      for (std::size_t i : group) sums.add(points[i]);
      result.push_back({fit(sums, prior, profile, params), sums, group});
    }
  }
  lines = std::move(result);
  sort_by_intercept(lines);
  return splits;
}

}  // namespace l2s::io::fan
