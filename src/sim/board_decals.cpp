// Sizes are those of real decals: a company logo of about 10 cm, label text
// of 1-1.5 cm capitals, an asset or shipping sticker of 10 x 6 cm with a
// barcode. A decal near a hole adds strong edges next to the rim the detector
// fits; a sticker crossing a rim makes that rim's contrast change along it.

#include "sim/board_decals.hpp"

#include "sim/footprint_filter.hpp"
#include "sim/random.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr std::uint64_t kDecalStream = 0xDECA1ULL;

double uniform(std::uint64_t seed, std::uint64_t index, double lo, double hi) {
  return lo + (hi - lo) * uniform01(hash_counters(seed, kDecalStream, index));
}

Eigen::Vector2d turned(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return Eigen::Vector2d(c * v.x() - s * v.y(), s * v.x() + c * v.y());
}

const Albedo kInk{0.05, Eigen::Array3d::Ones()};
const Albedo kLabelPaper{0.90, Eigen::Array3d::Ones()};
/// Printed logo colour: a saturated blue (B, G, R tint of luma 1).
const Albedo kLogoBlue{0.18, tint(2.6, 0.75, 0.35)};

}  // namespace

BoardDecals::BoardDecals(const Target& target, BoardTexture texture, std::uint64_t seed) {
  if (texture != BoardTexture::Logo && texture != BoardTexture::Sticker) return;
  const auto holes = target.hole_centers();
  const int hole = static_cast<int>(uniform(seed, 1, 0.0, 4.0 - 1e-9));
  const Eigen::Vector2d centre = holes[static_cast<std::size_t>(hole)];
  const double r = target.hole_radius;
  // Away from the board's centre, where there is board beside the hole.
  const Eigen::Vector2d outward(centre.x() < 0.0 ? -1.0 : 1.0, centre.y() < 0.0 ? -1.0 : 1.0);

  if (texture == BoardTexture::Logo) {
    // A ring with a bar across it, diagonally out from the hole, and two lines
    // of text between the hole and the board's top or bottom edge.
    const double logo = uniform(seed, 2, 0.035, 0.05);  // [m] outer radius
    const Eigen::Vector2d at = centre + (r + 0.02 + logo) * outward.normalized();
    shapes_.push_back(Shape{at, Eigen::Vector2d(logo, 0.7 * logo), 0.0, true, kLogoBlue});
    shapes_.push_back(Shape{at, Eigen::Vector2d(logo, 0.15 * logo), uniform(seed, 3, 0.0, kPi), false, kLogoBlue});
    const double height = uniform(seed, 4, 0.01, 0.015);
    const double length = uniform(seed, 5, 0.12, 0.2);
    const double top = centre.y() + outward.y() * (r + 0.015) + (outward.y() > 0.0 ? 2.6 * height : 0.0);
    for (int line = 0; line < 2; ++line)
      add_text(Eigen::Vector2d(centre.x() - 0.5 * length, top - line * 1.6 * height), 0.0,
               length * (line ? 0.7 : 1.0), height, mix64(seed ^ (0x7E47ULL + line)));
  } else {
    // A sticker whose middle lies on the rim: half of it on the board, its
    // edge crossing the rim twice.
    const double angle_on_rim = uniform(seed, 6, 0.0, 2.0 * kPi);
    const Eigen::Vector2d at = centre + r * Eigen::Vector2d(std::cos(angle_on_rim), std::sin(angle_on_rim));
    const double turn = uniform(seed, 7, -0.5, 0.5);
    const Eigen::Vector2d half(0.05, 0.03);
    shapes_.push_back(Shape{at, half, turn, false, kLabelPaper});
    // A barcode along its upper half and a line of text below.
    const std::uint64_t bars = mix64(seed ^ 0xBA4ULL);
    double x = -0.04;
    for (int k = 0; x < 0.04; ++k) {
      const double width = 0.001 + 0.002 * uniform01(mix64(bars + 2 * k));
      const double gap = 0.001 + 0.002 * uniform01(mix64(bars + 2 * k + 1));
      const Eigen::Vector2d mid(x + 0.5 * width, 0.008);
      shapes_.push_back(Shape{at + turned(mid, turn), Eigen::Vector2d(0.5 * width, 0.015), turn, false, kInk});
      x += width + gap;
    }
    add_text(at + turned(Eigen::Vector2d(-0.04, -0.017), turn), turn, 0.07, 0.006, mix64(seed ^ 0x7E47ULL));
  }
  low_ = Eigen::Vector2d::Constant(1e9);
  high_ = Eigen::Vector2d::Constant(-1e9);
  for (const Shape& s : shapes_) {
    const double reach = s.half_size.norm();
    low_ = low_.cwiseMin(s.centre - Eigen::Vector2d::Constant(reach));
    high_ = high_.cwiseMax(s.centre + Eigen::Vector2d::Constant(reach));
  }
}

void BoardDecals::add_text(const Eigen::Vector2d& start, double angle, double length, double height,
                           std::uint64_t seed) {
  // Capitals as solid blocks: at a pixel or more per stroke the detector sees
  // their outlines, which is what matters here, not the letters.
  double x = 0.0;
  for (int k = 0; x < length; ++k) {
    const double u = uniform01(mix64(seed + static_cast<std::uint64_t>(k)));
    if (u < 0.15) {  // a space between words
      x += 0.8 * height;
      continue;
    }
    const double width = height * (0.45 + 0.35 * u);
    const Eigen::Vector2d mid(x + 0.5 * width, -0.5 * height);
    shapes_.push_back(
        Shape{start + turned(mid, angle), Eigen::Vector2d(0.5 * width, 0.5 * height), angle, false, kInk});
    x += width + 0.2 * height;
  }
}

double BoardDecals::distance(const Shape& shape, const Eigen::Vector2d& uv) {
  const Eigen::Vector2d d = turned(uv - shape.centre, -shape.angle);
  if (shape.ring) {
    const double rho = d.norm();
    return std::max(rho - shape.half_size.x(), shape.half_size.y() - rho);
  }
  return std::max(std::abs(d.x()) - shape.half_size.x(), std::abs(d.y()) - shape.half_size.y());
}

Albedo BoardDecals::over(const Albedo& base, const Eigen::Vector2d& uv, double footprint) const {
  if (shapes_.empty() || (uv.array() < low_.array() - footprint).any() ||
      (uv.array() > high_.array() + footprint).any())
    return base;
  // Mix colours (gray * tint), not gray and tint apart; luma stays the gray.
  Eigen::Array3d colour = base.gray * base.tint;
  double gray = base.gray;
  for (const Shape& shape : shapes_) {
    const double share = edge_coverage(distance(shape, uv), footprint);
    if (share <= 0.0) continue;
    colour += share * (shape.paint.gray * shape.paint.tint - colour);
    gray += share * (shape.paint.gray - gray);
  }
  return Albedo{gray, gray > 1e-9 ? Eigen::Array3d(colour / gray) : Eigen::Array3d::Ones()};
}

}  // namespace l2s::sim::detail
