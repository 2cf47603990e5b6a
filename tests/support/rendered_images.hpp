#pragma once
// Renders of one camera of a simulated scene, and measures on them that the
// appearance tests share: the board face's gradients and a surface's mean.

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <cmath>

namespace l2s::sim {

inline StereoRig small_rig() {
  StereoRig rig;
  rig.width = 640;
  rig.height = 480;
  return rig;
}

inline CleanImage render_left(const Scene& scene, const Appearance& look, const StereoRig& rig = small_rig()) {
  StereoRenderer::Params params;
  params.appearance = look;
  return StereoRenderer(rig, params).render_camera(RayCaster(scene), 0);
}

/// Mean absolute differences between neighbouring pixels of the board's face,
/// along the image rows and across them, over pixels 2 px or more from the
/// face's edges and holes.
struct FaceGradients {
  double along = 0.0;
  double across = 0.0;
  int pixels = 0;
};

inline FaceGradients face_gradients(const CleanImage& image) {
  FaceGradients g;
  for (int v = 2; v + 2 < image.height; ++v)
    for (int u = 2; u + 2 < image.width; ++u) {
      bool inside = true;
      for (int d = -2; d <= 2; ++d)
        inside = inside && image.surface_at(u + d, v) == SurfaceId::Board &&
                 image.surface_at(u, v + d) == SurfaceId::Board;
      if (!inside) continue;
      g.along += std::abs(image.at(u + 1, v) - image.at(u, v));
      g.across += std::abs(image.at(u, v + 1) - image.at(u, v));
      ++g.pixels;
    }
  if (g.pixels > 0) g.along /= g.pixels, g.across /= g.pixels;
  return g;
}

inline double mean_of(const CleanImage& image, SurfaceId surface) {
  double sum = 0.0;
  int n = 0;
  for (int v = 0; v < image.height; ++v)
    for (int u = 0; u < image.width; ++u)
      if (image.surface_at(u, v) == surface) sum += image.at(u, v), ++n;
  return n ? sum / n : 0.0;
}

}  // namespace l2s::sim
