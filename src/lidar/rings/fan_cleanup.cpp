// Tidying the grown fan (see fan_cleanup.hpp).
#include "lidar/rings/fan_cleanup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace l2s::io::fan {

// Adjacent lines are one laser when one line explains their returns together
// as tightly as a laser's returns lie (the split of one laser's returns at the
// midpoint between two lines looks like two tight lines: a comparison of fits
// would keep them apart) and tighter than half the smallest laser spacing.
// Returns the number of merges.
std::size_t merge_lines(std::vector<Fitted>& lines, const OffsetProfile& profile,
                        const FanParams& params) {
  const double noise = typical_noise(lines, params);
  const OffsetPrior prior(lines, profile, params);
  std::vector<Fitted> merged;
  std::size_t merges = 0;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (k + 1 < lines.size()) {
      LineSums joint = lines[k].sums;
      joint.add(lines[k + 1].sums);
      if (lines[k].sums.n == 0 || lines[k + 1].sums.n == 0) {
        merged.push_back(lines[k]);
        continue;
      }
      const Line both = fit(joint, prior, profile, params);
      const double rms = std::sqrt(rss(joint, both) / std::max(1.0, joint.n - 2.0));
      const double per_radian = v_per_radian(both.t);
      // Two lasers are at least the minimum gap apart in elevation: lines
      // closer than half of it are one laser even when a few stray returns
      // widen their joint fit (up to the minimum gap; two lasers joined would
      // spread over half their spacing or more).
      const bool same_elevation =
          std::abs(lines[k + 1].line.t - lines[k].line.t) < 0.5 * params.min_gap * per_radian &&
          rms <= params.min_gap * per_radian;
      if (same_elevation || rms <= std::min(3.0 * noise, 0.5 * params.min_gap) * per_radian) {
        std::vector<std::size_t> members = lines[k].members;
        members.insert(members.end(), lines[k + 1].members.begin(), lines[k + 1].members.end());
        merged.push_back({both, joint, members});
        ++merges;
        ++k;  // the pair is taken; the next line is compared in the next round
        continue;
      }
    }
    merged.push_back(lines[k]);
  }
  lines = merged;
  sort_by_intercept(lines);
  return merges;
}

// Refits every line under the prior of the finished fan: a line whose own
// returns could not tell its offset (one distance only) took the prior of the
// moment, perhaps the wrong block's; its established neighbours now say.
void refit_all(std::vector<Fitted>& lines, const OffsetProfile& profile, const FanParams& params) {
  const OffsetPrior prior(lines, profile, params);
  for (Fitted& f : lines)
    if (f.sums.n > 0) f.line = fit(f.sums, prior, profile, params);
  sort_by_intercept(lines);
}

// Gives every return again to the line that alone explains it (classify) and
// refits each line to exactly those returns: assignments made while the fan
// grew are revisited, so a line that took a few wrong returns early sheds them,
// and one that only duplicates another keeps nothing. Lines left with fewer
// than min_points go.
void reassign(const std::vector<Point>& points, std::vector<Fitted>& lines,
              const OffsetProfile& profile, const FanParams& params) {
  const LineIndex index(plain(lines), true);
  std::vector<Fitted> fresh(lines.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Decision d = classify(lines, index.nearest(points[i]), points[i], params);
    if (d.verdict != Verdict::Accept) continue;
    fresh[d.line].sums.add(points[i]);
    fresh[d.line].members.push_back(i);
  }
  const OffsetPrior prior(lines, profile, params);
  std::vector<Fitted> kept;
  for (Fitted& f : fresh) {
    if (f.sums.n < static_cast<double>(params.min_points)) continue;
    f.line = fit(f.sums, prior, profile, params);
    kept.push_back(std::move(f));
  }
  lines = std::move(kept);
  sort_by_intercept(lines);
}

// Lines of real lasers do not cross where returns are dense: adjacent lasers
// differ in offset by millimetres (HDL-64E blocks: the upper block is both
// higher and offset more, so they part), and their lines meet only a few
// centimetres from the sensor (0.33 deg apart, they would need offsets 12 mm
// apart to meet 2 m out). Of two adjacent lines that cross beyond
// crossing_range, the one with fewer returns is a stray (a few returns of
// different lasers at one distance lined up) and is dissolved. Returns the
// number of lines dissolved.
std::size_t dissolve_crossing(std::vector<Fitted>& lines, const FanParams& params) {
  std::size_t dissolved = 0;
  for (std::size_t k = 0; k + 1 < lines.size();) {
    const Line& a = lines[k].line;
    const Line& b = lines[k + 1].line;
    const double crossing = (b.h < a.h) ? (b.t - a.t) / (a.h - b.h)  // [1/m]
                                        : std::numeric_limits<double>::infinity();
    if (crossing * params.crossing_range >= 1.0) {
      ++k;
      continue;
    }
    lines.erase(lines.begin() +
                static_cast<std::ptrdiff_t>(lines[k].sums.n < lines[k + 1].sums.n ? k : k + 1));
    ++dissolved;
    if (k > 0) --k;  // the new neighbours are compared next
  }
  return dissolved;
}

// A line with a handful of returns among lines with hundreds is dissolved:
// mostly a few returns that came before their own laser's line could take
// them, or a mixture of such. A real but sparse laser is found again in the
// whole cloud (assign_all), where its returns stay outliers of every line.
// Returns the number of lines dissolved.
std::size_t dissolve_strays(std::vector<Fitted>& lines) {
  constexpr double kStrayShare = 0.1;  // of the median line's returns
  std::vector<double> counts;
  for (const Fitted& f : lines) counts.push_back(f.sums.n);
  if (counts.size() < 3) return 0;
  std::nth_element(counts.begin(), counts.begin() + counts.size() / 2, counts.end());
  const double stray = kStrayShare * counts[counts.size() / 2];
  const std::size_t before = lines.size();
  lines.erase(
      std::remove_if(lines.begin(), lines.end(), [&](const Fitted& f) { return f.sums.n < stray; }),
      lines.end());
  return before - lines.size();
}

}  // namespace l2s::io::fan
