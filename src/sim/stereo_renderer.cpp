// Ray-cast rendering of the stereo pair. One ray per pixel centre
// everywhere; pixels whose centre key (surface, face, shadow) differs from a
// neighbour's (board borders, hole rims, object outlines, shadow edges) are
// re-rendered with n x n stratified samples, which anti-aliases edges at a
// small fraction of full supersampling.

#include <l2s/sim/stereo_renderer.hpp>

#include <l2s/error.hpp>

#include "sim/camera_response.hpp"
#include "sim/image_noise.hpp"
#include "sim/parallel.hpp"
#include "sim/pixel_rays.hpp"
#include "sim/shading.hpp"

#include <cmath>
#include <limits>

namespace l2s::sim {
namespace {

/// True when a neighbour of pixel (u, v) sees another surface, face or shadow state.
bool straddles_edge(const std::vector<int>& keys, int W, int H, int u, int v) {
  const int key = keys[static_cast<std::size_t>(v) * W + u];
  for (int dv = -1; dv <= 1; ++dv) {
    for (int du = -1; du <= 1; ++du) {
      const int uu = u + du, vv = v + dv;
      if (uu < 0 || vv < 0 || uu >= W || vv >= H) continue;
      if (keys[static_cast<std::size_t>(vv) * W + uu] != key) return true;
    }
  }
  return false;
}

/// Pass 2: n x n stratified samples for every pixel that straddles an edge.
void supersample_edges(const detail::PixelRays& rays, const detail::Shader& shader,
                       const std::vector<int>& keys, int n, int threads, CleanImage* image) {
  const int W = image->width, H = image->height, C = image->channels;
  std::vector<float> refined(image->intensity);
  detail::parallel_for(H, threads, [&](int v) {
    for (int u = 0; u < W; ++u) {
      if (!straddles_edge(keys, W, H, u, v)) continue;
      double sum[3] = {0.0, 0.0, 0.0};
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const Eigen::Vector3d d = rays.direction(u - 0.5 + (i + 0.5) / n, v - 0.5 + (j + 0.5) / n);
          const detail::Sample s = shader.shade(rays.origin(), d);
          for (int c = 0; c < C; ++c) sum[c] += s.value[static_cast<std::size_t>(c)];
        }
      }
      const std::size_t at = (static_cast<std::size_t>(v) * W + u) * C;
      for (int c = 0; c < C; ++c) refined[at + c] = static_cast<float>(sum[c] / (n * n));
    }
  });
  image->intensity.swap(refined);
}

}  // namespace

StereoRenderer::StereoRenderer(StereoRig rig) : StereoRenderer(rig, Params{}) {}

StereoRenderer::StereoRenderer(StereoRig rig, Params params) : rig_(rig), params_(params) {
  rig_.validate();
  params_.appearance.validate();
  if (params_.edge_samples < 1 || params_.edge_samples > 8)
    throw ParamError("renderer.edge_samples", "must be 1..8");
  if (!(params_.intensity_sigma0 >= 0.0))
    throw ParamError("renderer.intensity_sigma0", "must be >= 0");
}

CleanImage StereoRenderer::render_camera(const RayCaster& caster, int index) const {
  const detail::PixelRays rays(rig_, index);
  const int channels = params_.appearance.colour ? 3 : 1;
  const detail::Shader shader(caster, params_.appearance, params_.texture_seed, channels,
                              rays.pixel_angle());
  const int W = rig_.width;
  const int H = rig_.height;

  CleanImage image;
  image.width = W;
  image.height = H;
  image.channels = channels;
  image.intensity.assign(static_cast<std::size_t>(W) * H * channels, 0.0f);
  image.surface.assign(static_cast<std::size_t>(W) * H, SurfaceId::None);
  std::vector<int> keys(static_cast<std::size_t>(W) * H, 0);

  // Pass 1: the pixel-centre ray of every pixel.
  detail::parallel_for(H, params_.threads, [&](int v) {
    Eigen::Vector2d normal = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    for (int u = 0; u < W; ++u) {
      const detail::Sample s = shader.shade(rays.origin(), rays.direction(u, v, &normal));
      const std::size_t i = static_cast<std::size_t>(v) * W + u;
      for (int c = 0; c < channels; ++c)
        image.intensity[i * channels + c] = static_cast<float>(s.value[static_cast<std::size_t>(c)]);
      image.surface[i] = s.surface;
      keys[i] = s.key;
    }
  });

  if (params_.edge_samples > 1)
    supersample_edges(rays, shader, keys, params_.edge_samples, params_.threads, &image);
  detail::apply_camera_response(params_.appearance, rays.principal_point(), params_.threads, &image);
  return image;
}

CleanStereo StereoRenderer::render(const RayCaster& caster) const {
  return CleanStereo{render_camera(caster, 0), render_camera(caster, 1)};
}

Image StereoRenderer::add_noise(const CleanImage& clean, double noise_factor, std::uint64_t seed,
                                std::uint64_t frame, int camera_index) const {
  if (!(noise_factor >= 0.0)) throw ParamError("noise_factor", "must be >= 0");
  const double sigma = noise_factor * params_.intensity_sigma0;
  if (clean.channels == 1)
    return detail::add_gray_noise(clean, sigma, seed, frame, camera_index, params_.threads);
  return detail::add_colour_noise(clean, sigma, seed, frame, camera_index, params_.threads);
}

StereoImages StereoRenderer::add_noise(const CleanStereo& clean, double noise_factor,
                                       std::uint64_t seed, std::uint64_t frame) const {
  return StereoImages{add_noise(clean.left, noise_factor, seed, frame, 0),
                      add_noise(clean.right, noise_factor, seed, frame, 1)};
}

}  // namespace l2s::sim
