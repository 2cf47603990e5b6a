// Nearest-line search (see line_index.hpp). Predictions t + h u ascend with t
// at any u unless lines cross, which real lasers do only a few centimetres
// from the sensor; the neighbours checked around a candidate absorb that.
#include "lidar/rings/line_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace l2s::io::fan {
namespace {

constexpr double kBinU = 0.02;  // [1/m] predictions move by |dh| * 0.01 within a bin
constexpr double kMaxU = 2.0;   // [1/m] nearer returns (< 0.5 m, where lines converge) are bisected
constexpr double kMinCellV = 0.001;      // v units (0.06 deg), a sixth of the HDL-64E's spacing
constexpr double kMarginV = 0.05;        // cells beyond the outer lines
constexpr std::size_t kReach = 2;        // neighbours either side checked exactly after bisection
constexpr std::size_t kLookupReach = 1;  // and after a table lookup (cells are fine)

}  // namespace

LineIndex::LineIndex(const std::vector<Line>& lines, bool lookup) {
  for (const Line& line : lines) {
    t_.push_back(line.t);
    h_.push_back(line.h);
  }
  if (lookup && !t_.empty() && t_.size() <= std::numeric_limits<std::uint16_t>::max())
    build_lookup();
}

void LineIndex::build_lookup() {
  // Cells a quarter of the closest two lines' spacing: the cell's line and its
  // neighbours always hold the nearest one.
  double spacing = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < t_.size(); ++k) spacing = std::min(spacing, t_[k] - t_[k - 1]);
  cell_v_ = std::isfinite(spacing) ? std::max(kMinCellV, 0.25 * spacing) : kMinCellV;
  const auto bins = static_cast<std::size_t>(std::ceil(kMaxU / kBinU));
  for (std::size_t b = 0; b < bins; ++b) {
    const double u = (b + 0.5) * kBinU;
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t k = 0; k < t_.size(); ++k) {
      low = std::min(low, t_[k] + h_[k] * u);
      high = std::max(high, t_[k] + h_[k] * u);
    }
    cell_v0_.push_back(low - kMarginV);
    cell_begin_.push_back(static_cast<std::uint32_t>(cells_.size()));
    const auto count = static_cast<std::size_t>((high - low + 2.0 * kMarginV) / cell_v_) + 1;
    std::size_t k = 0;  // walks up with the cells: the nearest line never goes down
    for (std::size_t c = 0; c < count; ++c) {
      const double v = cell_v0_.back() + (c + 0.5) * cell_v_;
      while (k + 1 < t_.size() &&
             std::abs(v - t_[k + 1] - h_[k + 1] * u) <= std::abs(v - t_[k] - h_[k] * u))
        ++k;
      cells_.push_back(static_cast<std::uint16_t>(k));
    }
  }
  cell_begin_.push_back(static_cast<std::uint32_t>(cells_.size()));
}

Match LineIndex::nearest(const Point& p) const {
  if (t_.empty()) return {};
  if (!cells_.empty() && p.u >= 0.0 && p.u < kMaxU) {
    const auto bin = static_cast<std::size_t>(p.u / kBinU);
    const double cell = (p.v - cell_v0_[bin]) / cell_v_;
    const std::size_t size = cell_begin_[bin + 1] - cell_begin_[bin];
    if (cell >= 0.0 && cell < static_cast<double>(size))
      return best_around(p, cells_[cell_begin_[bin] + static_cast<std::size_t>(cell)],
                         kLookupReach);
  }
  return bisect(p);
}

Match LineIndex::bisect(const Point& p) const {
  // Branch-free lower bound: the first line predicting at or above v.
  std::size_t base = 0, n = t_.size();
  while (n > 1) {
    const std::size_t half = n / 2;
    base = t_[base + half - 1] + h_[base + half - 1] * p.u < p.v ? base + half : base;
    n -= half;
  }
  const std::size_t low = base + (t_[base] + h_[base] * p.u < p.v);
  return best_around(p, std::min(low, t_.size() - 1), kReach);
}

Match LineIndex::best_around(const Point& p, std::size_t center, std::size_t reach) const {
  const std::size_t first = center >= reach ? center - reach : 0;
  const std::size_t last = std::min(t_.size(), center + reach + 1);
  Match best;
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t k = first; k < last; ++k) {
    const double r = p.v - (t_[k] + h_[k] * p.u);
    if (std::abs(r) < smallest) smallest = std::abs(r), best = {static_cast<int>(k), r};
  }
  return best;
}

}  // namespace l2s::io::fan
