#pragma once
// What users stick or print on a board's face beside its texture, placed
// relative to the holes since that is where they disturb a detector: a logo
// with a text label beside one hole, or a sticker whose edge crosses one rim.
// Markers (MarkerTexture) are printed over them.

#include <l2s/sim/appearance.hpp>
#include <l2s/target.hpp>

#include "sim/materials.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace l2s::sim::detail {

class BoardDecals {
 public:
  /// Decals of `texture` (BoardTexture::Logo, Sticker; none for the others)
  /// on `target`'s face, placed by `seed`.
  BoardDecals(const Target& target, BoardTexture texture, std::uint64_t seed);

  bool empty() const { return shapes_.empty(); }
  /// `base` with the decals at `uv` (board frame, metres) painted over it,
  /// their edges filtered by the pixel's `footprint` [m].
  Albedo over(const Albedo& base, const Eigen::Vector2d& uv, double footprint) const;

 private:
  /// A filled rectangle turned by `angle`, or a ring (half_size.x() its
  /// outer and half_size.y() its inner radius).
  struct Shape {
    Eigen::Vector2d centre;
    Eigen::Vector2d half_size;
    double angle = 0.0;
    bool ring = false;
    Albedo paint;
  };
  /// [m] signed distance from `uv` to the shape's outline (negative inside).
  static double distance(const Shape& shape, const Eigen::Vector2d& uv);
  void add_text(const Eigen::Vector2d& start, double angle, double length, double height, std::uint64_t seed);

  std::vector<Shape> shapes_;  ///< painted in order
  Eigen::Vector2d low_, high_;  ///< bounding box of every shape
};

}  // namespace l2s::sim::detail
