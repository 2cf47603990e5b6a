#pragma once
// Counter-based random numbers: every draw is a pure function of (seed and
// indices), so results never depend on thread count or evaluation order, and
// are the same on every platform (std::normal_distribution is not).

#include <cmath>
#include <cstdint>

namespace l2s::sim::detail {

/// SplitMix64 finaliser: a good 64-bit mixing function.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// Hash of a seed and up to four counters.
inline std::uint64_t hash_counters(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0,
                                   std::uint64_t c = 0, std::uint64_t d = 0) {
  std::uint64_t h = mix64(seed);
  h = mix64(h ^ a);
  h = mix64(h ^ (b + 0x51ED27ULL));
  h = mix64(h ^ (c + 0xA5A5A5ULL));
  return mix64(h ^ (d + 0x3C3C3CULL));
}

/// Uniform in (0, 1): 53 random bits, never exactly 0 (safe for log).
inline double uniform01(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/// Standard normal from one 64-bit hash (Box-Muller on two 32-bit halves).
inline double standard_normal(std::uint64_t bits) {
  const double u1 = (static_cast<double>(bits >> 32) + 0.5) * (1.0 / 4294967296.0);
  const double u2 = (static_cast<double>(bits & 0xFFFFFFFFULL) + 0.5) * (1.0 / 4294967296.0);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

}  // namespace l2s::sim::detail
