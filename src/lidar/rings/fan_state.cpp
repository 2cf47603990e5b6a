// The shared vocabulary of the fan fit (see fan_state.hpp).
#include "lidar/rings/fan_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace l2s::io::fan {

double rss(const LineSums& s, const Line& l) {
  return std::max(0.0, s.svv - 2.0 * l.t * s.sv - 2.0 * l.h * s.suv + l.t * l.t * s.n +
                           2.0 * l.t * l.h * s.su + l.h * l.h * s.suu);
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kEstablished = 0.003;     // [m] sigma of h below which a line is established
constexpr double kNeighbourSigma = 0.004;  // [m] neighbours' offsets differ by mm
constexpr double kJump = 0.015;            // [m] a step between blocks of lasers

Hypotheses between(double low, double high, double w, double sigma) {
  if (std::abs(high - low) <= kJump)
    return {{{{(1.0 - w) * low + w * high, std::max(sigma, std::abs(high - low))}, {}}}, 1};
  return {{{{low, sigma}, {high, sigma}}}, 2};
}

}  // namespace

OffsetPrior::OffsetPrior(const std::vector<Fitted>& lines, const OffsetProfile& profile,
                         const FanParams& params)
    : profile_(profile), params_(params) {
  for (const Fitted& f : lines)
    if (f.line.scale * std::sqrt(f.line.cov(1, 1)) < kEstablished) {
      t_.push_back(f.line.t);
      h_.push_back(f.line.h);
    }
}

Hypotheses OffsetPrior::at(double t) const {
  const double skip = 0.5 * params_.min_gap * v_per_radian(t);
  const auto above = std::upper_bound(t_.begin(), t_.end(), t + skip) - t_.begin();
  const auto below = std::lower_bound(t_.begin(), t_.end(), t - skip) - t_.begin() - 1;
  if (above < static_cast<std::ptrdiff_t>(t_.size()) && below >= 0) {
    const double w = (t - t_[below]) / (t_[above] - t_[below]);
    return between(h_[below], h_[above], w, kNeighbourSigma);
  }
  const auto [low, high] = profile_.sides(t);
  return between(low, high, 0.5, params_.offset_sigma);
}

Line fit(const LineSums& sums, const OffsetPrior& prior, const OffsetProfile& profile,
         const FanParams& params) {
  const double t0 = (sums.sv - profile.global() * sums.su) / sums.n;
  const Hypotheses hypotheses = prior.at(t0);
  const double per_radian = v_per_radian(t0);
  const double noise = params.noise * per_radian;
  Line best;
  double best_cost = kInfinity;
  for (int k = 0; k < hypotheses.count; ++k) {
    const auto [mean, sigma] = hypotheses.options[k];
    const Line line = fit_line(sums, mean, sigma, noise, params.noise_floor * per_radian);
    const double dh = (line.h - mean) / sigma;
    const double cost = rss(sums, line) / (noise * noise) + dh * dh;
    if (cost < best_cost) best_cost = cost, best = line;
  }
  return best;
}

std::vector<Line> plain(const std::vector<Fitted>& lines) {
  std::vector<Line> out;
  for (const Fitted& f : lines) out.push_back(f.line);
  return out;
}

void sort_by_intercept(std::vector<Fitted>& lines) {
  std::sort(lines.begin(), lines.end(),
            [](const Fitted& a, const Fitted& b) { return a.line.t < b.line.t; });
}

double typical_noise(const std::vector<Fitted>& lines, const FanParams& params) {
  std::vector<double> scales;
  for (const Fitted& f : lines) scales.push_back(f.line.scale / v_per_radian(f.line.t));
  if (scales.empty()) return params.noise_floor;
  std::nth_element(scales.begin(), scales.begin() + scales.size() / 2, scales.end());
  return std::max(params.noise_floor, scales[scales.size() / 2]);
}

Decision classify(const std::vector<Fitted>& lines, const Match& nearest, const Point& p,
                  const FanParams& params) {
  constexpr int kReach = 2;          // lines either side of the nearest that are asked too
  constexpr double kClearWin = 3.0;  // a winner this many times more likely (in sigmas)
  if (nearest.line < 0) return {};
  const int first = std::max(0, nearest.line - kReach);
  const int last = std::min(static_cast<int>(lines.size()), nearest.line + kReach + 1);
  // Squared z-scores throughout: no square root per return and line.
  const double gate2 = params.gate * params.gate;
  int best = -1, plausible = 0;
  double best_z2 = kInfinity, second_z2 = kInfinity;
  for (int k = first; k < last; ++k) {
    const Line& line = lines[k].line;
    const double r = p.v - line.predict(p.u);
    const double z2 = r * r / line.variance(p.u);
    if (z2 > gate2) continue;
    ++plausible;
    if (z2 < best_z2)
      second_z2 = best_z2, best_z2 = z2, best = k;
    else
      second_z2 = std::min(second_z2, z2);
  }
  if (plausible == 0) return {Verdict::Outlier, -1};
  if (plausible == 1 || kClearWin * kClearWin * std::max(best_z2, 0.25) < second_z2)
    return {Verdict::Accept, best};
  return {Verdict::Uncertain, best};
}

}  // namespace l2s::io::fan
