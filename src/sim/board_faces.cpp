// Printed faces. Sizes are those of real prints: a speckle print for stereo
// or image correlation wants dots of three to five pixels at the working
// distance, i.e. a few millimetres on a board 1-5 m away, covering about 40 %
// of the face; a noise print for longer ranges blotches of centimetres;
// oriented strand board flakes of 4-8 x 1.5-3 cm.

#include "sim/board_faces.hpp"

#include "sim/footprint_filter.hpp"
#include "sim/random.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {
namespace {

constexpr double kPaper = 0.85;  // reflectance of white printing paper
constexpr double kInk = 0.05;    // of black toner or ink
constexpr std::uint64_t kSpeckleStream = 0x5BEC1EULL;
constexpr std::uint64_t kNoisePrintStream = 0x9015EULL;
constexpr std::uint64_t kFlakeStream = 0xF1A4EULL;
constexpr std::uint64_t kPaintStream = 0x9A1E7ULL;

}  // namespace

Albedo speckle_print(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed) {
  constexpr double kCell = 0.008;                    // [m] one dot per cell
  constexpr double kMinRadius = 0.25 * kCell, kMaxRadius = 0.45 * kCell;
  // Mean share of the face the dots cover, pi E[r^2] / cell^2.
  const double mean_cover = 3.141592653589793 *
                            (kMinRadius * kMinRadius + kMinRadius * kMaxRadius + kMaxRadius * kMaxRadius) /
                            (3.0 * kCell * kCell);
  const double i = std::floor(uv.x() / kCell), j = std::floor(uv.y() / kCell);
  const std::uint64_t h = hash_counters(seed, kSpeckleStream, static_cast<std::uint64_t>(static_cast<std::int64_t>(i)),
                                        static_cast<std::uint64_t>(static_cast<std::int64_t>(j)));
  const double radius = kMinRadius + (kMaxRadius - kMinRadius) * uniform01(h);
  // The dot lies wholly inside its cell, so only this cell's dot can cover the point.
  const double room = 0.5 * kCell - radius;
  const Eigen::Vector2d centre((i + 0.5) * kCell + room * (2.0 * uniform01(mix64(h ^ 1ULL)) - 1.0),
                               (j + 0.5) * kCell + room * (2.0 * uniform01(mix64(h ^ 2ULL)) - 1.0));
  const double exact = edge_coverage((uv - centre).norm() - radius, footprint);
  // Dots finer than the pixel fade to the print's mean gray instead of aliasing.
  const double cover = mean_cover + kept_amplitude(footprint, kCell) * (exact - mean_cover);
  return Albedo{kPaper + cover * (kInk - kPaper), Eigen::Array3d::Ones()};
}

Albedo noise_print(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed) {
  // Two octaves of noise from 3 cm, pushed towards black and white as a
  // printer's halftone of a high-contrast pattern would be.
  const double n = filtered_noise(uv.x(), uv.y(), 0.03, 2, seed ^ kNoisePrintStream, footprint);
  const double pushed = std::tanh(3.0 * n);
  return Albedo{0.5 * (kPaper + kInk) + 0.5 * (kPaper - kInk) * pushed, Eigen::Array3d::Ones()};
}

Albedo chipboard(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed) {
  constexpr double kCell = 0.03;  // [m] one flake per cell
  constexpr int kReach = 2;       // cells: a flake reaches at most 4 cm from its centre
  constexpr double kResin = 0.30, kMeanFlake = 0.60;
  struct Cover {
    std::uint64_t order;
    double share;
    double gray;
  };
  Cover covers[(2 * kReach + 1) * (2 * kReach + 1)];
  int count = 0;
  const auto ci = static_cast<std::int64_t>(std::floor(uv.x() / kCell));
  const auto cj = static_cast<std::int64_t>(std::floor(uv.y() / kCell));
  for (std::int64_t i = ci - kReach; i <= ci + kReach; ++i)
    for (std::int64_t j = cj - kReach; j <= cj + kReach; ++j) {
      const std::uint64_t h = hash_counters(seed, kFlakeStream, static_cast<std::uint64_t>(i),
                                            static_cast<std::uint64_t>(j));
      const Eigen::Vector2d centre((static_cast<double>(i) + uniform01(mix64(h ^ 1ULL))) * kCell,
                                   (static_cast<double>(j) + uniform01(mix64(h ^ 2ULL))) * kCell);
      const double angle = 3.141592653589793 * uniform01(mix64(h ^ 3ULL));
      const double half_length = 0.02 + 0.02 * uniform01(mix64(h ^ 4ULL));
      const double half_width = 0.0075 + 0.0075 * uniform01(mix64(h ^ 5ULL));
      const Eigen::Vector2d d = uv - centre;
      const double along = std::abs(std::cos(angle) * d.x() + std::sin(angle) * d.y());
      const double across = std::abs(-std::sin(angle) * d.x() + std::cos(angle) * d.y());
      // Signed distance to the flake's outline (a rectangle; exact outside its corners).
      const double distance = std::max(along - half_length, across - half_width);
      const double share = edge_coverage(distance, footprint);
      if (share > 0.0) covers[count++] = Cover{h, share, 0.45 + 0.30 * uniform01(mix64(h ^ 6ULL))};
    }
  // Flakes lie on one another in the order of their hash: paint them bottom up.
  std::sort(covers, covers + count, [](const Cover& a, const Cover& b) { return a.order < b.order; });
  double gray = kResin;
  for (int k = 0; k < count; ++k) gray += covers[k].share * (covers[k].gray - gray);
  // Fine fibres along each flake are below a pixel but at the closest range.
  gray += 0.04 * filtered_noise(uv.x(), uv.y(), 0.004, 2, seed ^ kFlakeStream, footprint);
  // Flakes finer than the pixel average out to the board's mean: flakes of
  // mean area 4 E[half length] E[half width] cover 1 - exp(-area / cell) of it.
  const double covered = 1.0 - std::exp(-4.0 * 0.03 * 0.01125 / (kCell * kCell));
  const double mean = kResin + covered * (kMeanFlake - kResin);
  gray = mean + kept_amplitude(footprint, kCell) * (gray - mean);
  return Albedo{std::clamp(gray, 0.02, 0.98), tint(0.55, 0.80, 1.25)};
}

Albedo black_paint(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed) {
  return Albedo{0.05 + 0.008 * filtered_noise(uv.x(), uv.y(), 0.05, 3, seed ^ kPaintStream, footprint),
                Eigen::Array3d::Ones()};
}

Albedo white_paint(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed) {
  return Albedo{0.86 + 0.008 * filtered_noise(uv.x(), uv.y(), 0.05, 3, seed ^ kPaintStream, footprint),
                Eigen::Array3d::Ones()};
}

Albedo laminate(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed) {
  return Albedo{0.80 + 0.01 * filtered_noise(uv.x(), uv.y(), 0.08, 3, seed ^ kPaintStream, footprint),
                Eigen::Array3d::Ones()};
}

Albedo unprinted_board() { return Albedo{0.78, Eigen::Array3d::Ones()}; }

}  // namespace l2s::sim::detail
