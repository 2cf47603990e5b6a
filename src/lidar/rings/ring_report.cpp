// Judging a recovered ring structure. Scan lines of a spinning lidar keep
// their returns tight around each laser's model compared with the spacing of
// the lasers (fill ~0.1); a non-repetitive scan (Livox) spreads returns evenly
// over the elevations (fill ~0.5, or one "ring" degrees wide).
#include "lidar/rings/ring_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace l2s::io {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979;
constexpr double kRingFreeContrast = 3.0;  // even spread: ~1 (an Avia window measured up to 2.2)
constexpr double kDoubtContrast = 5.0;     // noisy HDL-64E (0.05 deg on 0.33): ~40
constexpr double kWideRing = 0.5 / kDeg;   // [rad] a single "ring" wider than this is no scan line
constexpr double kSparseRing = 0.02;       // a ring with < 2 % of the median returns
constexpr double kOverlapContrast = 5.0;   // two lasers barely told apart: ~5; clean: tens
constexpr int kMostRings = 256;            // no spinning lidar has more lasers
constexpr std::size_t kReturnsPerRing = 10;  // fewer per ring: too many rings
// One or two lines for this many returns are no spinning lidar's sweep of a
// scene: it has 16 lasers or more, and one or two could not show a board's
// holes anyway. Such a scan is a solid-state one, e.g. a board leaning back
// and cropped, whose returns all fit one laser model z = d tan(e) + h.
constexpr std::size_t kManyReturns = 1000;

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof(text), pattern, a, b, c);
  return text;
}

void add_doubt(RingRecoveryReport& report, const std::string& reason) {
  report.doubtful = true;
  report.doubt += (report.doubt.empty() ? "" : "; ") + reason;
}

void decide_structure(RingRecoveryReport& report) {
  const std::size_t lasers = report.lasers.size();
  if (lasers == 0) {
    report.structure_reason = "no valid returns";
    return;
  }
  std::vector<double> widths;
  for (const LaserFit& laser : report.lasers) widths.push_back(laser.rms);
  std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
  if (widths[widths.size() / 2] > kWideRing) {
    report.structure = ScanStructure::RingFree;
    report.structure_reason = format(
        "returns spread %.1f deg (rms, median of %.0f fitted lines) around each line: no scan "
        "lines",
        widths[widths.size() / 2] * kDeg, static_cast<double>(lasers));
    return;
  }
  if (lasers <= 2 && report.points >= kManyReturns) {
    report.structure = ScanStructure::RingFree;
    report.structure_reason = format(
        "only %.0f line(s) for %.0f returns, where a spinning lidar's sweep has 16 or more: no scan lines",
        static_cast<double>(lasers), static_cast<double>(report.points));
    return;
  }
  if (lasers > 1 && report.contrast < kRingFreeContrast) {
    report.structure = ScanStructure::RingFree;
    report.structure_reason = format(
        "returns fill the elevations between the %.0f fitted lines evenly (contrast %.1f; scan "
        "lines have tens): no scan lines",
        static_cast<double>(lasers), report.contrast);
    return;
  }
  report.structure_reason = format(
      "%.0f scan lines; returns lie within %.0f %% of the half gap to the next line (median)",
      static_cast<double>(lasers), 100.0 * report.fill);
}

void check_doubts(RingRecoveryReport& report) {
  const std::size_t lasers = report.lasers.size();
  if (report.structure != ScanStructure::Rings || lasers == 0) return;
  if (report.rings > kMostRings)
    add_doubt(report, format("%.0f rings, more than any spinning lidar has", report.rings));
  if (report.points < kReturnsPerRing * static_cast<std::size_t>(report.rings))
    add_doubt(report,
              format("%.0f rings for %.0f returns (fewer than %.0f returns a ring)", report.rings,
                     static_cast<double>(report.points), static_cast<double>(kReturnsPerRing)));
  if (lasers > 1 && report.contrast < kDoubtContrast)
    add_doubt(report, format("returns spread between the rings (contrast %.1f; scan lines: tens)",
                             report.contrast));
  for (const LaserFit& laser : report.lasers)
    if (laser.points < kSparseRing * report.median_points) {
      add_doubt(report, format("ring %.0f has %.0f returns, the median ring %.0f", laser.ring,
                               static_cast<double>(laser.points), report.median_points));
      break;  // one example says enough
    }
  for (const LaserFit& laser : report.lasers)
    if (laser.contrast > 0.0 && laser.contrast < kOverlapContrast) {
      add_doubt(report, format("ring %.0f overlaps a neighbour (contrast %.1f: nearly as many "
                               "returns next to the middle between them as on the ring)",
                               laser.ring, laser.contrast));
      break;
    }
}

// Over the returns (every stride-th), q = |residual| / (half the gap to the
// neighbouring line on the return's side at its distance): fill is the median
// of q, contrast the count of q < 1/4 over that of q > 3/4, over all returns
// and per line. Returns nearer than 2 m do not count: there the lines of
// densely packed lasers run into each other whatever the structure. Returns
// the contrast per line.
std::vector<double> fill_and_contrast(const std::vector<fan::Line>& lines,
                                      const std::vector<fan::Point>& points,
                                      const std::vector<int>& labels, RingRecoveryReport& report) {
  constexpr std::size_t kSample = 20000;
  constexpr double kNearU = 0.5;  // [1/m]
  std::vector<double> inner(lines.size(), 0.0), outer(lines.size(), 0.0);
  if (lines.size() < 2) return inner;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / kSample);
  std::vector<double> fills;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const int k = labels[i];
    const fan::Point& p = points[i];
    if (k < 0 || p.u > kNearU) continue;
    const double r = p.v - lines[k].predict(p.u);
    const bool up = (r >= 0.0 && k + 1 < static_cast<int>(lines.size())) || k == 0;
    const double gap = std::abs(lines[up ? k + 1 : k - 1].predict(p.u) - lines[k].predict(p.u));
    if (!(gap > 0.0)) continue;
    fills.push_back(std::min(1.0, std::abs(r) / (0.5 * gap)));
    inner[k] += fills.back() < 0.25;
    outer[k] += fills.back() > 0.75;
  }
  double all_inner = 0.0, all_outer = 0.0;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    all_inner += inner[k];
    all_outer += outer[k];
    inner[k] = inner[k] + outer[k] > 0.0 ? inner[k] / std::max(1.0, outer[k]) : 0.0;
  }
  if (fills.empty()) return inner;
  report.contrast = all_inner / std::max(1.0, all_outer);
  std::nth_element(fills.begin(), fills.begin() + fills.size() / 2, fills.end());
  report.fill = fills[fills.size() / 2];
  return inner;
}

}  // namespace

void describe_lines(const std::vector<fan::Line>& lines, const std::vector<int>& ring_of_line,
                    const std::vector<fan::Point>& points, const std::vector<int>& labels,
                    RingRecoveryReport& report) {
  std::vector<std::size_t> count(lines.size(), 0);
  std::vector<double> squares(lines.size(), 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int k = labels[i];
    if (k < 0) continue;
    const double r = (points[i].v - lines[k].predict(points[i].u)) / fan::v_per_radian(lines[k].t);
    ++count[k];
    squares[k] += r * r;
    total += r * r;
  }
  const std::vector<double> contrast = fill_and_contrast(lines, points, labels, report);
  report.lasers.clear();
  report.points = 0;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (count[k] == 0) continue;
    report.lasers.push_back({ring_of_line[k], lines[k].elevation(), lines[k].h,
                             std::sqrt(squares[k] / count[k]), count[k], contrast[k]});
    report.points += count[k];
  }
  std::sort(report.lasers.begin(), report.lasers.end(),
            [](const LaserFit& a, const LaserFit& b) { return a.elevation < b.elevation; });
  report.residual_rms = report.points > 0 ? std::sqrt(total / report.points) : 0.0;
}

std::string to_string(RingSource source) {
  switch (source) {
    case RingSource::Field:
      return "field";
    case RingSource::OrganisedRows:
      return "organised rows";
    default:
      return "laser model";
  }
}

std::string to_string(ScanStructure structure) {
  return structure == ScanStructure::RingFree ? "ring-free" : "rings";
}

void finish_report(RingRecoveryReport& report) {
  std::vector<std::size_t> counts;
  for (const LaserFit& laser : report.lasers) counts.push_back(laser.points);
  if (!counts.empty()) {
    std::sort(counts.begin(), counts.end());
    report.min_points = counts.front();
    const std::size_t n = counts.size();
    report.median_points = n % 2 ? counts[n / 2] : 0.5 * (counts[n / 2 - 1] + counts[n / 2]);
  }
  decide_structure(report);
  check_doubts(report);
}

std::string RingRecoveryReport::summary() const {
  std::string text = to_string(source) + ": " + std::to_string(rings) + " rings";
  if (static_cast<std::size_t>(rings) != lasers.size())
    text += " (" + std::to_string(lasers.size()) + " with returns)";
  text += format(", returns per ring min %.0f median %.0f, residual %.3f deg rms",
                 static_cast<double>(min_points), median_points, residual_rms * kDeg);
  text += "; " + to_string(structure) + ": " + structure_reason;
  if (doubtful) text += "; DOUBTFUL: " + doubt;
  if (!note.empty()) text += "; " + note;
  return text;
}

}  // namespace l2s::io
