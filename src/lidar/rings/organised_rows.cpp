// Rings from the rows of an organised cloud. A driver may store a sweep as one
// row per laser (padding missing returns with NaN); other organised clouds
// have rows that are not lasers (a column per firing, a depth image). The rows
// are lasers when each row's returns fit one laser model (z = d tan(e) + h, so
// offset beams pass) tightly compared with the spacing between the rows.
#include <l2s/error.hpp>
#include <l2s/io/ring_recovery.hpp>

#include "lidar/rings/line_index.hpp"
#include "lidar/rings/ring_model_input.hpp"
#include "lidar/rings/ring_report.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace l2s::io {
namespace {

constexpr double kPriorSigma =
    0.3;  // [m] rows fit their own offset, this only steadies one-distance rows
constexpr double kNoise = 0.0004;  // [v] expected elevation noise
constexpr double kTight = 0.5;  // a row's 90th-percentile residual below this share of half the gap
constexpr double kGoodRows = 0.9;  // share of rows that must be tight

struct Row {
  std::size_t row = 0;
  fan::Line line;
  double spread = 0.0;  // [v] 90th percentile of |residual|
  ModelInput input;
};

// One line through a row's returns, refitted once without those beyond three
// rms (a stray return must not tilt it).
Row fit_row(const LidarCloud& cloud, std::size_t row, std::size_t width) {
  Row result;
  result.row = row;
  result.input = model_input(cloud, row * width, (row + 1) * width);
  const auto& points = result.input.points;
  fan::LineSums sums;
  for (const fan::Point& p : points) sums.add(p);
  result.line = fan::fit_line(sums, 0.0, kPriorSigma, kNoise, 0.0);
  fan::LineSums kept;
  for (const fan::Point& p : points)
    if (std::abs(p.v - result.line.predict(p.u)) <= 3.0 * result.line.scale) kept.add(p);
  if (kept.n >= 2) result.line = fan::fit_line(kept, 0.0, kPriorSigma, kNoise, 0.0);
  std::vector<double> residuals;
  for (const fan::Point& p : points) residuals.push_back(std::abs(p.v - result.line.predict(p.u)));
  const std::size_t q = static_cast<std::size_t>(0.9 * (residuals.size() - 1));
  std::nth_element(residuals.begin(), residuals.begin() + q, residuals.end());
  result.spread = residuals[q];
  return result;
}

// Empty when the rows look like lasers, else why not.
std::string rows_are_not_lasers(const std::vector<Row>& rows, double min_gap) {
  if (rows.size() < 2) return "fewer than two rows with returns";
  std::size_t tight = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double below = k > 0 ? rows[k].line.t - rows[k - 1].line.t : 1e300;
    const double above = k + 1 < rows.size() ? rows[k + 1].line.t - rows[k].line.t : 1e300;
    const double gap = std::min(below, above);
    if (gap < min_gap * fan::v_per_radian(rows[k].line.t))
      return "rows " + std::to_string(rows[k].row) + " and its neighbour lie at one elevation";
    tight += rows[k].spread <= kTight * 0.5 * gap;
  }
  if (tight < kGoodRows * rows.size())
    return std::to_string(rows.size() - tight) + " of " + std::to_string(rows.size()) +
           " rows spread over more than a quarter of the gap to the next row";
  return {};
}

// Ring of each row: the row number when rows ascend in elevation, counted
// from the last row when they descend (top row first), else the rank.
std::vector<int> ring_of_rows(const std::vector<Row>& by_elevation, std::size_t height) {
  std::vector<std::size_t> order;
  for (const Row& row : by_elevation) order.push_back(row.row);
  const bool ascending = std::is_sorted(order.begin(), order.end());
  const bool descending = std::is_sorted(order.rbegin(), order.rend());
  std::vector<int> rings;
  for (std::size_t k = 0; k < by_elevation.size(); ++k)
    rings.push_back(ascending    ? static_cast<int>(order[k])
                    : descending ? static_cast<int>(height - 1 - order[k])
                                 : static_cast<int>(k));
  return rings;
}

}  // namespace

RingRecoveryReport rings_from_rows(LidarCloud& cloud, std::size_t height,
                                   const RingRecoveryParams& params) {
  params.validate();
  if (height == 0 || cloud.size() % height != 0)
    throw ParamError("height", std::to_string(height) + " rows cannot hold " +
                                   std::to_string(cloud.size()) + " points");
  const std::size_t width = cloud.size() / height;
  std::vector<Row> rows;
  for (std::size_t r = 0; r < height; ++r) {
    Row row = fit_row(cloud, r, width);
    if (!row.input.points.empty()) rows.push_back(std::move(row));
  }
  std::sort(rows.begin(), rows.end(),
            [](const Row& a, const Row& b) { return a.line.t < b.line.t; });
  const std::string why_not = rows_are_not_lasers(rows, params.min_gap);
  if (!why_not.empty()) {
    RingRecoveryReport report = recover_ring_structure(cloud, params);
    report.note = "rows of the organised cloud are not lasers (" + why_not + ")";
    return report;
  }
  const std::vector<int> rings = ring_of_rows(rows, height);
  cloud.ring.assign(cloud.size(), 0);
  std::vector<fan::Line> lines;
  std::vector<fan::Point> points;
  std::vector<int> labels;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    lines.push_back(rows[k].line);
    for (std::size_t i = 0; i < rows[k].input.points.size(); ++i) {
      cloud.ring[rows[k].input.index[i]] = static_cast<std::uint16_t>(rings[k]);
      points.push_back(rows[k].input.points[i]);
      labels.push_back(static_cast<int>(k));
    }
  }
  RingRecoveryReport report;
  report.source = RingSource::OrganisedRows;
  describe_lines(lines, rings, points, labels, report);
  report.rings = *std::max_element(rings.begin(), rings.end()) + 1;
  finish_report(report);
  return report;
}

}  // namespace l2s::io
