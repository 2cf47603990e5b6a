#include <l2s/viz/overlay.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace l2s {
namespace {

// Near is red, far is blue: red -> yellow -> green -> cyan -> blue, as BGR.
std::array<std::uint8_t, 3> range_colour(double t) {
  static const double kStops[5][3] = {{0, 0, 255}, {0, 255, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}};
  const double s = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(3, static_cast<int>(s));
  const double f = s - i;
  std::array<std::uint8_t, 3> bgr{};
  for (int c = 0; c < 3; ++c)
    bgr[c] = static_cast<std::uint8_t>(std::lround(kStops[i][c] * (1 - f) + kStops[i + 1][c] * f));
  return bgr;
}

Image to_bgr(const Image& image) {
  if (image.channels == 3) return image;
  Image bgr(image.width, image.height, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) bgr.pixels[3 * i + c] = image.pixels[i];
  return bgr;
}

}  // namespace

Image render_overlay(const Image& left, const LidarCloud& sweep, const CameraInfo& camera,
                     const Eigen::Isometry3d& T_lidar_camera, const OverlayParams& params) {
  Image out = to_bgr(left);
  const Eigen::Isometry3d T_camera_lidar = T_lidar_camera.inverse();
  const int radius = std::clamp(params.point_radius, 0, 10);
  for (const auto& p_lidar : sweep.points) {
    if (!p_lidar.allFinite()) continue;
    const Eigen::Vector3d p_camera = T_camera_lidar * p_lidar;
    const Eigen::Vector2d uv = camera.project(p_camera);
    if (!uv.allFinite()) continue;
    const int u = static_cast<int>(std::lround(uv.x()));
    const int v = static_cast<int>(std::lround(uv.y()));
    if (u < -radius || v < -radius || u >= out.width + radius || v >= out.height + radius) continue;
    const auto colour = range_colour((p_lidar.norm() - params.min_range) /
                                     std::max(1e-9, params.max_range - params.min_range));
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx) {
        const int x = u + dx, y = v + dy;
        if (dx * dx + dy * dy > radius * radius || x < 0 || y < 0 || x >= out.width || y >= out.height)
          continue;
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = colour[c];
      }
  }
  return out;
}

}  // namespace l2s
