#pragma once
// Renders the stereo pair of a static scene by ray casting, as the rig writes
// it (rectified, or raw through the physical lenses): several samples per
// pixel where a pixel straddles two surfaces or a shadow edge (anti-aliased
// hole rims, board borders, shadows), procedural textures that stereo
// matching can lock onto, Lambert shading under the appearance's light, the
// camera's response (exposure, vignetting, blur, gamma), then per-frame
// Gaussian intensity noise N(0, (K * 0.007)^2) on a 0..1 scale (paper,
// Sec. IV-B) and 8-bit gray or BGR output.

#include <l2s/export.hpp>
#include <l2s/sim/appearance.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/sim/stereo_rig.hpp>
#include <l2s/types.hpp>

#include <cstdint>
#include <vector>

namespace l2s::sim {

/// One noise-free rendered image with the surface seen at each pixel centre.
struct CleanImage {
  int width = 0;                    ///< [px]
  int height = 0;                   ///< [px]
  int channels = 1;                 ///< 1 (gray) or 3 (B, G, R interleaved)
  std::vector<float> intensity;     ///< row-major, 0..1 (values above 1 clip at white)
  std::vector<SurfaceId> surface;   ///< row-major, surface hit by the pixel-centre ray

  float at(int u, int v, int c = 0) const {
    return intensity[(static_cast<std::size_t>(v) * width + u) * channels + c];
  }
  SurfaceId surface_at(int u, int v) const { return surface[static_cast<std::size_t>(v) * width + u]; }
};

struct CleanStereo {
  CleanImage left;
  CleanImage right;
};

/// The 8-bit images of one frame (gray, or BGR for a colour appearance).
struct StereoImages {
  Image left;
  Image right;
};

class L2S_SIM_EXPORT StereoRenderer {
 public:
  struct Params {
    int edge_samples = 4;         ///< per axis where a pixel straddles surfaces (4 -> 16 samples), 1..8
    double intensity_sigma0 = 0.007;  ///< 0..1 scale, noise at factor K = 1 (paper)
    std::uint64_t texture_seed = 0x1234abcdULL;  ///< selects the procedural textures
    int threads = 0;              ///< worker threads, 0 = hardware concurrency
    Appearance appearance;        ///< materials, light, camera response (defaults: the paper suite's look)
  };

  // Two constructors: see LidarSimulator (nested Params as default argument).
  explicit StereoRenderer(StereoRig rig);
  StereoRenderer(StereoRig rig, Params params);

  /// Renders the noise-free pair; the scene is static, so do this once per dataset.
  CleanStereo render(const RayCaster& caster) const;
  /// One noise-free image of camera `index` (0 = left, 1 = right).
  CleanImage render_camera(const RayCaster& caster, int index) const;

  /// Adds fresh noise to the clean pair. Noise is drawn from (seed, frame,
  /// camera, row, column) alone, so the bytes never depend on the thread count.
  StereoImages add_noise(const CleanStereo& clean, double noise_factor, std::uint64_t seed,
                         std::uint64_t frame) const;
  Image add_noise(const CleanImage& clean, double noise_factor, std::uint64_t seed,
                  std::uint64_t frame, int camera_index) const;

  const StereoRig& rig() const { return rig_; }
  const Params& params() const { return params_; }

 private:
  StereoRig rig_;
  Params params_;
};

}  // namespace l2s::sim
