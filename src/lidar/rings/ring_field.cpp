// Whether a sweep's ring field gives its scan lines (see check_ring_field in
// l2s/io/ring_recovery.hpp). Each value's returns are fitted with the laser
// model of ring recovery (laser_line.hpp): a laser index keeps them within
// a few hundredths of a degree of one line, and the lines of successive
// indices climb (or fall) one after the other. A solid-state lidar's line or
// head number, a packet counter or a constant spread each value over degrees
// or put several values on one line.
#include <l2s/io/ring_recovery.hpp>

#include "lidar/rings/laser_line.hpp"
#include "lidar/rings/ring_model_input.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace l2s::io {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979;
/// One or two values for this many returns are no laser indices: a spinning
/// lidar's sweep of a scene has 16 lasers or more (as ring recovery judges
/// recovered lines, ring_report.cpp).
constexpr std::size_t kManyReturns = 1000;
/// [rad] a laser's returns stay within hundredths of a degree of its line
/// (range noise moves them along it); half a degree is no scan line.
constexpr double kWideLine = 0.5 / kDeg;
/// Values with fewer returns are too thin to place (stray returns, a beam
/// that barely saw anything).
constexpr std::size_t kFitReturns = 10;
// The ridge prior of the line fit: offsets of a few centimetres to decimetres
// (laser_line.hpp), residuals at a lidar's elevation noise.
constexpr double kOffsetSigma = 0.2;  // [m]
constexpr double kNoise = 0.0005;     // [v] ~0.03 deg
constexpr double kFloor = 1e-5;

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char text[200];
  std::snprintf(text, sizeof(text), pattern, a, b, c, d);
  return text;
}

RingFieldCheck unusable(std::string reason) { return {false, std::move(reason)}; }

struct ValueLine {
  int value = 0;
  fan::Line line;
  double mean_u = 0.0;  // [1/m] where its returns are
  double spread = 0.0;  // [rad] rms about the line
};

}  // namespace

RingFieldCheck check_ring_field(const LidarCloud& cloud) {
  if (!cloud.has_ring() || cloud.ring.size() != cloud.size()) return {};  // no field, or one the branch rejects
  const ModelInput input = model_input(cloud);
  std::map<int, fan::LineSums> sums;
  for (std::size_t i = 0; i < input.points.size(); ++i) sums[cloud.ring[input.index[i]]].add(input.points[i]);
  if (input.points.size() >= kManyReturns && sums.size() <= 2)
    return unusable(format("%.0f value(s) for %.0f returns, where a spinning lidar's sweep has 16 or more",
                           static_cast<double>(sums.size()), static_cast<double>(input.points.size())));

  std::vector<ValueLine> lines;
  for (const auto& [value, value_sums] : sums) {
    if (value_sums.n < kFitReturns) continue;
    const fan::Line line = fan::fit_line(value_sums, 0.0, kOffsetSigma, kNoise, kFloor);
    lines.push_back({value, line, value_sums.su / value_sums.n, line.scale / fan::v_per_radian(line.t)});
  }
  if (lines.empty()) return {};  // too few returns to judge: taken at its word
  std::vector<double> spreads;
  for (const ValueLine& line : lines) spreads.push_back(line.spread);
  std::nth_element(spreads.begin(), spreads.begin() + spreads.size() / 2, spreads.end());
  const double spread = spreads[spreads.size() / 2];
  if (spread > kWideLine)
    return unusable(format("the returns of one value spread %.1f deg about a scan line (median of %.0f "
                           "values), where a laser's stay within hundredths of a degree",
                           spread * kDeg, static_cast<double>(lines.size())));

  // Successive values must be successive lasers: apart by more than their
  // spread, all climbing or all falling (drivers number from the bottom or
  // from the top). Lines are compared where their returns are, as lasers
  // with different origin offsets may cross nearer than any return; a pair
  // or two out of step is such a crossing, a quarter of them is no order.
  std::size_t together = 0, rising = 0, falling = 0;
  const ValueLine* first_together = nullptr;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const ValueLine& a = lines[k - 1];
    const ValueLine& b = lines[k];
    const double u = 0.5 * (a.mean_u + b.mean_u);
    const double step = b.line.predict(u) - a.line.predict(u);
    if (std::abs(step) <= a.line.scale + b.line.scale) {
      if (together++ == 0) first_together = &a;
    } else {
      ++(step > 0.0 ? rising : falling);
    }
  }
  const std::size_t pairs = lines.size() - 1;
  if (pairs > 0 && 4 * together > pairs)
    return unusable(format("%.0f of %.0f successive values lie on one scan line (values %.0f and %.0f)",
                           static_cast<double>(together), static_cast<double>(pairs), first_together->value,
                           (first_together + 1)->value));
  const std::size_t against = std::min(rising, falling);
  if (pairs > 0 && 4 * against > pairs)
    return unusable(format("the values do not follow elevation: %.0f of %.0f successive values climb, %.0f fall",
                           static_cast<double>(rising), static_cast<double>(pairs), static_cast<double>(falling)));
  return {};
}

}  // namespace l2s::io
