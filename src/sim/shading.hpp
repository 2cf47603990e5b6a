#pragma once
// The light a camera ray brings back: the first surface along it, lit by the
// appearance's sun (Lambert) and ambient light, with a shadow ray towards the
// sun when hard shadows are on, and the sun's highlight on a glossy board; or
// the sky when it hits nothing.

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/ray_caster.hpp>

#include "sim/board_decals.hpp"
#include "sim/marker_texture.hpp"
#include "sim/materials.hpp"

#include <array>
#include <cstdint>

namespace l2s::sim::detail {

/// One shaded ray.
struct Sample {
  std::array<double, 3> value{};  ///< linear radiance: gray in [0], or B, G, R
  int key = 0;                    ///< equal keys: same surface, face and shadow state
  SurfaceId surface = SurfaceId::None;
};

class Shader {
 public:
  /// `channels` 1 (gray) or 3 (BGR); `pixel_angle` [rad] sets the texture filter.
  Shader(const RayCaster& caster, const Appearance& appearance, std::uint64_t texture_seed,
         int channels, double pixel_angle);

  Sample shade(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

 private:
  bool in_shadow(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const;
  /// The marker cell printed where `hit` is (MarkerTexture::cell), -1 for none.
  int printed_cell(const Hit& hit) const;

  const RayCaster& caster_;
  Appearance look_;
  Materials materials_;
  BoardDecals decals_;
  MarkerTexture markers_;
  int channels_;
  double pixel_angle_;
};

}  // namespace l2s::sim::detail
