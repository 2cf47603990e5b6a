#include "sim/shading.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {
namespace {

/// Identifies the face seen by a ray; pixels with different keys straddle an edge.
int surface_key(const Hit& hit, bool shadowed) {
  return (static_cast<int>(hit.surface) * 16 + hit.part) * 2 + (shadowed ? 1 : 0);
}

/// [m] Shadow rays start this far off the surface so they do not hit it again.
constexpr double kShadowOffset = 1e-5;

/// Reflectance of the printed markers: matte black ink on white paper.
constexpr double kInkBlack = 0.04;
constexpr double kPaperWhite = 0.85;

/// A glossy laminate's highlight (Blinn-Phong): its peak radiance, above the
/// diffuse white's, and the exponent that gives it a half width of about 5 deg
/// about the sun's mirror direction.
constexpr double kGlossPeak = 1.2;
constexpr double kGlossExponent = 200.0;

}  // namespace

Shader::Shader(const RayCaster& caster, const Appearance& appearance, std::uint64_t texture_seed,
               int channels, double pixel_angle)
    : caster_(caster),
      look_(appearance),
      materials_(appearance, texture_seed),
      decals_(caster.scene().target, appearance.board, texture_seed),
      markers_(caster.scene().target, caster.scene().marker_turns),
      channels_(channels),
      pixel_angle_(pixel_angle) {}

bool Shader::in_shadow(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const {
  return caster_.cast(point + kShadowOffset * normal, look_.to_light).hit();
}

int Shader::printed_cell(const Hit& hit) const {
  if (markers_.empty() || hit.surface != SurfaceId::Board ||
      hit.part != static_cast<std::uint8_t>(BoardPart::Front))
    return -1;
  return markers_.cell(hit.uv);
}

Sample Shader::shade(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
  const Hit hit = caster_.cast(origin, direction);
  Sample sample;
  sample.surface = hit.surface;
  Albedo albedo;
  double light = 1.0;  // the sky glows by itself
  double highlight = 0.0;  // white, added to the diffuse light
  if (!hit.hit()) {
    albedo = materials_.sky(direction);
  } else {
    Eigen::Vector3d n = hit.normal;
    if (n.dot(direction) > 0.0) n = -n;  // the side facing the viewer
    const double facing = std::max(0.1, -n.dot(direction));
    const double footprint = hit.t * pixel_angle_ / facing;
    albedo = materials_.surface(hit, footprint);
    const bool front = hit.surface == SurfaceId::Board && hit.part == static_cast<std::uint8_t>(BoardPart::Front);
    if (front && !decals_.empty()) albedo = decals_.over(albedo, hit.uv, footprint);
    const int marker_cell = printed_cell(hit);
    if (marker_cell >= 0) albedo = Albedo{marker_cell ? kInkBlack : kPaperWhite, Eigen::Array3d::Ones()};
    const double lambert = std::max(0.0, n.dot(look_.to_light));
    const bool shadowed =
        look_.shadows && lambert > 0.0 && in_shadow(origin + hit.t * direction, n);
    light = look_.ambient + (1.0 - look_.ambient) * (shadowed ? 0.0 : lambert);
    if (front && look_.board == BoardTexture::Glossy && !shadowed && lambert > 0.0) {
      const Eigen::Vector3d half = (look_.to_light - direction).normalized();
      highlight = (1.0 - look_.ambient) * kGlossPeak * std::pow(std::max(0.0, n.dot(half)), kGlossExponent);
    }
    // Marker cells get keys of their own, so the renderer anti-aliases their
    // edges like the board's outline (the corners must be sharp to sub-pixel).
    sample.key = surface_key(hit, shadowed) + (marker_cell + 1) * 1024;
  }
  if (channels_ == 1) {
    sample.value[0] = albedo.gray * light + highlight;
  } else {
    for (int c = 0; c < 3; ++c)
      sample.value[static_cast<std::size_t>(c)] = albedo.gray * albedo.tint[c] * light + highlight;
  }
  return sample;
}

}  // namespace l2s::sim::detail
