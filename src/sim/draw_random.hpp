#pragma once
// Draws for the randomised scenes from a generator's raw 64-bit output (the
// std distributions differ between standard libraries; the engine's output
// does not), so a seed draws the same scene on every platform.

#include <array>
#include <cstddef>
#include <random>

namespace l2s::sim::detail {

/// Uniform in [lo, hi).
inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0));
}

inline bool chance(std::mt19937_64& rng, double p) { return uniform(rng, 0.0, 1.0) < p; }

/// Index drawn with the given weights.
template <std::size_t N>
std::size_t pick(std::mt19937_64& rng, const std::array<double, N>& weights) {
  double total = 0.0;
  for (double w : weights) total += w;
  double x = uniform(rng, 0.0, total);
  for (std::size_t i = 0; i + 1 < N; ++i) {
    if (x < weights[i]) return i;
    x -= weights[i];
  }
  return N - 1;
}

}  // namespace l2s::sim::detail
