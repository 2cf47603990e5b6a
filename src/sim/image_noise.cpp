#include "sim/image_noise.hpp"

#include "sim/parallel.hpp"
#include "sim/random.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace l2s::sim::detail {
namespace {

std::uint8_t quantise(double value) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(value * 255.0), 0L, 255L));
}

/// Standard normal quantile of p in (0.5, 1): Newton's method from 0, which
/// rises monotonically to the root because the CDF is concave there.
double upper_quantile(double p) {
  double x = 0.0;
  for (int i = 0; i < 100; ++i) {
    const double cdf = 0.5 * std::erfc(-x / std::sqrt(2.0));
    const double pdf = std::exp(-0.5 * x * x) / std::sqrt(2.0 * 3.141592653589793);
    const double step = (p - cdf) / pdf;
    x += step;
    if (step < 1e-12) break;
  }
  return x;
}

/// Quantiles of (i + 0.5) / 65536, built once.
const std::vector<float>& normal_table() {
  static const std::vector<float> table = [] {
    std::vector<float> t(65536);
    for (int i = 0; i < 32768; ++i) {
      const auto q = static_cast<float>(upper_quantile((32768 + i + 0.5) / 65536.0));
      t[static_cast<std::size_t>(32768 + i)] = q;
      t[static_cast<std::size_t>(32767 - i)] = -q;
    }
    return t;
  }();
  return table;
}

}  // namespace

Image add_gray_noise(const CleanImage& clean, double sigma, std::uint64_t seed, std::uint64_t frame,
                     int camera_index, int threads) {
  const int W = clean.width;
  Image image(W, clean.height, 1);
  parallel_for(clean.height, threads, [&](int v) {
    const float* in = clean.intensity.data() + static_cast<std::size_t>(v) * W;
    std::uint8_t* out = image.pixels.data() + static_cast<std::size_t>(v) * W;
    for (int u = 0; u < W; u += 2) {
      // One hash feeds two pixels: Box-Muller gives a cosine and a sine draw.
      double n0 = 0.0, n1 = 0.0;
      if (sigma > 0.0) {
        const std::uint64_t bits = hash_counters(seed, frame, camera_index, v, u);
        const double u1 = (static_cast<double>(bits >> 32) + 0.5) * (1.0 / 4294967296.0);
        const double u2 = (static_cast<double>(bits & 0xFFFFFFFFULL) + 0.5) * (1.0 / 4294967296.0);
        const double r = sigma * std::sqrt(-2.0 * std::log(u1));
        n0 = r * std::cos(6.283185307179586 * u2);
        n1 = r * std::sin(6.283185307179586 * u2);
      }
      out[u] = quantise(in[u] + n0);
      if (u + 1 < W) out[u + 1] = quantise(in[u + 1] + n1);
    }
  });
  return image;
}

Image add_colour_noise(const CleanImage& clean, double sigma, std::uint64_t seed,
                       std::uint64_t frame, int camera_index, int threads) {
  const int W = clean.width, C = clean.channels;
  const int count = W * C;  // values per row
  Image image(W, clean.height, C);
  const std::vector<float>& table = normal_table();
  const auto s = static_cast<float>(sigma);
  parallel_for(clean.height, threads, [&](int v) {
    const float* in = clean.intensity.data() + static_cast<std::size_t>(v) * count;
    std::uint8_t* out = image.pixels.data() + static_cast<std::size_t>(v) * count;
    // Salted apart from the gray stream; one row key, then one mix per four draws.
    const std::uint64_t row = hash_counters(seed, frame, camera_index, v, 0xC0102ULL);
    for (int i = 0; i < count; i += 4) {
      std::uint64_t bits = sigma > 0.0 ? mix64(row + static_cast<std::uint64_t>(i)) : 0;
      for (int k = i; k < std::min(i + 4, count); ++k, bits >>= 16) {
        const float noise = sigma > 0.0 ? s * table[bits & 0xFFFFULL] : 0.0f;
        const float value = (in[k] + noise) * 255.0f;
        out[k] = static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
      }
    }
  });
  return image;
}

}  // namespace l2s::sim::detail
