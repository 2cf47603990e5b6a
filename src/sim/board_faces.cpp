// Printed faces. Sizes are those of real prints: a speckle print for stereo
// or image correlation wants dots of three to five pixels at the working
// distance, i.e. a few millimetres on a board 1-5 m away, covering about 40 %
// of the face.

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

/// Share of a pixel of footprint `footprint` [m] covered by a disc whose edge
/// is `distance` [m] away (negative inside): a linear ramp across the footprint.
double disc_coverage(double distance, double footprint) {
  if (footprint <= 1e-9) return distance < 0.0 ? 1.0 : 0.0;
  return std::clamp(0.5 - distance / footprint, 0.0, 1.0);
}

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
  const double exact = disc_coverage((uv - centre).norm() - radius, footprint);
  // Dots finer than the pixel fade to the print's mean gray instead of aliasing.
  const double cover = mean_cover + kept_amplitude(footprint, kCell) * (exact - mean_cover);
  return Albedo{kPaper + cover * (kInk - kPaper), Eigen::Array3d::Ones()};
}

Albedo unprinted_board() { return Albedo{0.78, Eigen::Array3d::Ones()}; }

}  // namespace l2s::sim::detail
