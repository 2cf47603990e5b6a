// Ray-cast rendering of the rectified stereo pair. One ray per pixel centre
// everywhere; pixels whose centre surface differs from a neighbour's (board
// borders, hole rims, object outlines) are re-rendered with n x n stratified
// samples, which anti-aliases edges at a small fraction of full supersampling.

#include <l2s/sim/stereo_renderer.hpp>

#include <l2s/error.hpp>

#include "sim/parallel.hpp"
#include "sim/random.hpp"
#include "sim/texture.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

/// Light from above, behind and a little left of the cameras (body frame),
/// pointing towards the light.
const Eigen::Vector3d kToLight = Eigen::Vector3d(-1.0, 0.35, 0.6).normalized();
constexpr double kAmbient = 0.35;

/// Identifies the face seen by a ray; pixels with different keys straddle an edge.
int surface_key(const Hit& hit) { return static_cast<int>(hit.surface) * 16 + hit.part; }

double shade(const Hit& hit, const Eigen::Vector3d& direction, std::uint64_t seed) {
  const double albedo = detail::albedo(hit, seed);
  if (!hit.hit()) return albedo;
  Eigen::Vector3d n = hit.normal;
  if (n.dot(direction) > 0.0) n = -n;  // the side facing the viewer
  const double lambert = std::max(0.0, n.dot(kToLight));
  return albedo * (kAmbient + (1.0 - kAmbient) * lambert);
}

/// Ray geometry of one camera.
struct CameraRays {
  Eigen::Vector3d origin;
  Eigen::Matrix3d R_cambody_optical;
  double fx, cx, cy;

  Eigen::Vector3d direction(double u, double v) const {
    return (R_cambody_optical * Eigen::Vector3d((u - cx) / fx, (v - cy) / fx, 1.0)).normalized();
  }
};

}  // namespace

StereoRenderer::StereoRenderer(StereoRig rig) : StereoRenderer(rig, Params{}) {}

StereoRenderer::StereoRenderer(StereoRig rig, Params params) : rig_(rig), params_(params) {
  rig_.validate();
  if (params_.edge_samples < 1 || params_.edge_samples > 8)
    throw ParamError("renderer.edge_samples", "must be 1..8");
  if (!(params_.intensity_sigma0 >= 0.0))
    throw ParamError("renderer.intensity_sigma0", "must be >= 0");
}

CleanImage StereoRenderer::render_camera(const RayCaster& caster, int index) const {
  const Eigen::Isometry3d T = rig_.T_cambody_optical(index);
  const CameraRays rays{T.translation(), T.linear(), rig_.fx(), rig_.cx(), rig_.cy()};
  const int W = rig_.width;
  const int H = rig_.height;
  const std::uint64_t seed = params_.texture_seed;

  CleanImage image;
  image.width = W;
  image.height = H;
  image.intensity.assign(static_cast<std::size_t>(W) * H, 0.0f);
  image.surface.assign(static_cast<std::size_t>(W) * H, SurfaceId::None);
  std::vector<int> keys(static_cast<std::size_t>(W) * H, 0);

  // Pass 1: the pixel-centre ray of every pixel.
  detail::parallel_for(H, params_.threads, [&](int v) {
    for (int u = 0; u < W; ++u) {
      const Eigen::Vector3d d = rays.direction(u, v);
      const Hit hit = caster.cast(rays.origin, d);
      const std::size_t i = static_cast<std::size_t>(v) * W + u;
      image.intensity[i] = static_cast<float>(shade(hit, d, seed));
      image.surface[i] = hit.surface;
      keys[i] = surface_key(hit);
    }
  });

  // Pass 2: supersample pixels that straddle an edge (any 8-neighbour differs).
  const int n = params_.edge_samples;
  if (n > 1) {
    std::vector<float> refined(image.intensity);
    detail::parallel_for(H, params_.threads, [&](int v) {
      for (int u = 0; u < W; ++u) {
        const int key = keys[static_cast<std::size_t>(v) * W + u];
        bool edge = false;
        for (int dv = -1; dv <= 1 && !edge; ++dv) {
          for (int du = -1; du <= 1; ++du) {
            const int uu = u + du, vv = v + dv;
            if (uu < 0 || vv < 0 || uu >= W || vv >= H) continue;
            if (keys[static_cast<std::size_t>(vv) * W + uu] != key) {
              edge = true;
              break;
            }
          }
        }
        if (!edge) continue;
        double sum = 0.0;
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            const Eigen::Vector3d d =
                rays.direction(u - 0.5 + (i + 0.5) / n, v - 0.5 + (j + 0.5) / n);
            sum += shade(caster.cast(rays.origin, d), d, seed);
          }
        }
        refined[static_cast<std::size_t>(v) * W + u] = static_cast<float>(sum / (n * n));
      }
    });
    image.intensity.swap(refined);
  }
  return image;
}

CleanStereo StereoRenderer::render(const RayCaster& caster) const {
  return CleanStereo{render_camera(caster, 0), render_camera(caster, 1)};
}

Image StereoRenderer::add_noise(const CleanImage& clean, double noise_factor, std::uint64_t seed,
                                std::uint64_t frame, int camera_index) const {
  if (!(noise_factor >= 0.0)) throw ParamError("noise_factor", "must be >= 0");
  const int W = clean.width;
  Image image(W, clean.height, 1);
  const double sigma = noise_factor * params_.intensity_sigma0;
  detail::parallel_for(clean.height, params_.threads, [&](int v) {
    const float* in = clean.intensity.data() + static_cast<std::size_t>(v) * W;
    std::uint8_t* out = image.pixels.data() + static_cast<std::size_t>(v) * W;
    for (int u = 0; u < W; u += 2) {
      // One hash feeds two pixels: Box-Muller gives a cosine and a sine draw.
      double n0 = 0.0, n1 = 0.0;
      if (sigma > 0.0) {
        const std::uint64_t bits = detail::hash_counters(seed, frame, camera_index, v, u);
        const double u1 = (static_cast<double>(bits >> 32) + 0.5) * (1.0 / 4294967296.0);
        const double u2 = (static_cast<double>(bits & 0xFFFFFFFFULL) + 0.5) * (1.0 / 4294967296.0);
        const double r = sigma * std::sqrt(-2.0 * std::log(u1));
        n0 = r * std::cos(6.283185307179586 * u2);
        n1 = r * std::sin(6.283185307179586 * u2);
      }
      const auto quantise = [](double value) {
        return static_cast<std::uint8_t>(std::clamp(std::lround(value * 255.0), 0L, 255L));
      };
      out[u] = quantise(in[u] + n0);
      if (u + 1 < W) out[u + 1] = quantise(in[u + 1] + n1);
    }
  });
  return image;
}

StereoImages StereoRenderer::add_noise(const CleanStereo& clean, double noise_factor,
                                       std::uint64_t seed, std::uint64_t frame) const {
  return StereoImages{add_noise(clean.left, noise_factor, seed, frame, 0),
                      add_noise(clean.right, noise_factor, seed, frame, 1)};
}

}  // namespace l2s::sim
