// Ring recovery by per-laser models (see l2s/io/ring_recovery.hpp and
// laser_fan.hpp): fit the fan, give every return its laser, number the lasers
// from the lowest, and judge the result. Beams without returns are recognised
// where the spacing is regular: a gap of ~k local spacings between two lasers
// skips k - 1 indices. The local spacing is the median of up to four gaps on
// each side; it is trusted only when no gap there is much smaller than it
// (uniform sensors, and HDL-64E's two blocks), so sensors with a deliberately
// uneven fan (VLP-32C) are numbered consecutively instead.
#include <l2s/io/ring_recovery.hpp>

#include <l2s/error.hpp>

#include "lidar/rings/laser_fan.hpp"
#include "lidar/rings/ring_model_input.hpp"
#include "lidar/rings/ring_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace l2s::io {
namespace {

constexpr int kWindow = 4;               // gaps looked at on each side
constexpr double kRegularSpacing = 0.6;  // smallest gap / median at least this = regular

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Index of each laser (ascending elevations), skipping indices of beams that
// returned nothing.
std::vector<int> number(const std::vector<double>& elevations, bool infer_missing) {
  std::vector<int> index(elevations.size(), 0);
  std::vector<double> gaps;
  for (std::size_t k = 1; k < elevations.size(); ++k)
    gaps.push_back(elevations[k] - elevations[k - 1]);
  for (std::size_t j = 0; j < gaps.size(); ++j) {
    int steps = 1;
    std::vector<double> window;
    for (std::size_t w = j >= kWindow ? j - kWindow : 0; w <= j + kWindow && w < gaps.size(); ++w)
      if (w != j) window.push_back(gaps[w]);
    if (infer_missing && window.size() >= 2) {
      const double spacing = median(window);
      const double smallest = *std::min_element(window.begin(), window.end());
      if (spacing > 0.0 && smallest >= kRegularSpacing * spacing)
        steps = std::max(1, static_cast<int>(std::lround(gaps[j] / spacing)));
    }
    index[j + 1] = std::min(index[j] + steps, int{std::numeric_limits<std::uint16_t>::max()});
  }
  return index;
}

fan::FanParams fan_params(const RingRecoveryParams& params) {
  fan::FanParams fan;
  fan.min_gap = params.min_gap;
  fan.min_points = static_cast<std::size_t>(params.min_points_per_ring);
  fan.max_points = static_cast<std::size_t>(params.max_fit_points);
  fan.profile.offset_range = params.max_offset;
  return fan;
}

// Lines with fewer returns than a ring needs give theirs to the nearest other
// line (stray returns fold into a ring, as a ring of two returns is no ring).
void drop_thin_lines(const std::vector<fan::Point>& points, std::vector<fan::Line>& lines,
                     std::vector<int>& labels, std::size_t min_points) {
  std::vector<std::size_t> count(lines.size(), 0);
  for (int k : labels)
    if (k >= 0) ++count[k];
  std::vector<int> renumber(lines.size(), -1);
  std::vector<fan::Line> kept;
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (count[k] >= min_points) {
      renumber[k] = static_cast<int>(kept.size());
      kept.push_back(lines[k]);
    }
  if (kept.size() == lines.size() || kept.empty()) return;
  const fan::LineIndex index(kept);
  for (std::size_t i = 0; i < points.size(); ++i)
    labels[i] = labels[i] < 0              ? -1
                : renumber[labels[i]] >= 0 ? renumber[labels[i]]
                                           : index.nearest(points[i]).line;
  lines = std::move(kept);
}

// All returns as one laser, for sweeps with fewer returns than a laser needs.
fan::Line one_line(const std::vector<fan::Point>& points) {
  constexpr double kNoise = 0.0004;  // [v] any positive value: one line takes every return
  fan::LineSums sums;
  for (const fan::Point& p : points) sums.add(p);
  return fan::fit_line(sums, 0.0, 0.01, kNoise, kNoise);
}

}  // namespace

void RingRecoveryParams::validate() const {
  if (!(min_gap > 0.0) || !std::isfinite(min_gap))
    throw ParamError("min_gap", "must be a positive angle in radians");
  if (min_points_per_ring < 1) throw ParamError("min_points_per_ring", "must be at least 1");
  if (!(max_offset > 0.0) || !std::isfinite(max_offset))
    throw ParamError("max_offset", "must be a positive distance in metres");
  if (max_fit_points < 100) throw ParamError("max_fit_points", "must be at least 100");
}

RingRecoveryReport recover_ring_structure(LidarCloud& cloud, const RingRecoveryParams& params) {
  params.validate();
  cloud.ring.assign(cloud.size(), 0);
  const ModelInput input = model_input(cloud);
  RingRecoveryReport report;
  report.source = RingSource::LaserModel;
  if (!input.points.empty()) {
    const fan::FanParams fan_settings = fan_params(params);
    fan::Fan fan = fan::fit_fan(input.points, fan_settings);
    if (fan.lines.empty()) fan.lines = {one_line(input.points)};  // too few returns for lasers
    std::vector<int> labels = fan::assign_all(input.points, fan, fan_settings);
    drop_thin_lines(input.points, fan.lines, labels, fan_settings.min_points);
    std::vector<double> elevations;
    for (const fan::Line& line : fan.lines) elevations.push_back(line.elevation());
    const std::vector<int> ring_of_line = number(elevations, params.infer_missing_beams);
    for (std::size_t i = 0; i < input.points.size(); ++i)
      if (labels[i] >= 0)
        cloud.ring[input.index[i]] = static_cast<std::uint16_t>(ring_of_line[labels[i]]);
    describe_lines(fan.lines, ring_of_line, input.points, labels, report);
    report.rings = ring_of_line.empty() ? 0 : ring_of_line.back() + 1;
  }
  finish_report(report);
  return report;
}

int recover_rings(LidarCloud& cloud, const RingRecoveryParams& params) {
  return recover_ring_structure(cloud, params).rings;
}

ScanClassification classify_scan(const LidarCloud& cloud, const RingRecoveryParams& params) {
  std::string field;
  if (cloud.has_ring()) {
    const RingFieldCheck check = check_ring_field(cloud);
    if (check.usable) return {ScanStructure::Rings, "the sweep's ring field gives its scan lines"};
    field = "ring field ignored (" + check.reason + "); ";
  }
  LidarCloud copy;
  copy.points = cloud.points;
  const RingRecoveryReport report = recover_ring_structure(copy, params);
  return {report.structure, field + report.structure_reason};
}

}  // namespace l2s::io
