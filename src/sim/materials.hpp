#pragma once
// What each surface of the simulated scene looks like under an Appearance:
// diffuse reflectance (gray level and colour tint) per surface point, and the
// sky. The paper suite's looks come from texture.hpp unchanged, so default
// scenes keep their exact bytes; the other looks filter texture detail finer
// than a pixel (box-filtered joints, attenuated noise octaves) so that fine
// patterns shade like a camera would integrate them instead of aliasing.

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/ray_caster.hpp>

#include <Eigen/Core>
#include <cstdint>

namespace l2s::sim::detail {

/// Diffuse reflectance: colour (B, G, R) = gray * tint, with the tint's luma
/// (0.114 B + 0.587 G + 0.299 R) equal to 1, so a gray image is the luma of
/// the colour image.
struct Albedo {
  double gray = 0.0;
  Eigen::Array3d tint = Eigen::Array3d::Ones();
};

/// A tint (B, G, R) scaled to luma 1.
inline Eigen::Array3d tint(double b, double g, double r) {
  const double luma = 0.114 * b + 0.587 * g + 0.299 * r;
  return Eigen::Array3d(b, g, r) / luma;
}

class Materials {
 public:
  Materials(const Appearance& appearance, std::uint64_t seed);

  /// Reflectance at `hit` (which must have hit something); `footprint` [m] is
  /// the size of the pixel on the surface there.
  Albedo surface(const Hit& hit, double footprint) const;
  /// What a ray that hits nothing sees (direction in the camera body frame).
  Albedo sky(const Eigen::Vector3d& direction_cambody) const;

 private:
  Albedo board(const Hit& hit, double footprint) const;
  Albedo wall(const Hit& hit, double footprint) const;

  Appearance look_;
  std::uint64_t seed_;
  double background_gray_;  ///< mean reflectance of the wall, for LowContrast
};

}  // namespace l2s::sim::detail
