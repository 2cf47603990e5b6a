#pragma once
// Plain data shared by every part of l2scalib: sweeps and images.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace l2s {

/// One lidar sweep as parallel arrays, so that stages read the points as plain
/// Eigen vectors and look up per-point attributes by index.
struct LidarCloud {
  std::vector<Eigen::Vector3d> points;  ///< [m] lidar frame (x forward, y left, z up); may hold NaN
  std::vector<float> intensity;         ///< one per point, or empty when unknown
  std::vector<std::uint16_t> ring;      ///< laser index (0 = lowest beam), one per point, or empty

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_intensity() const { return !intensity.empty(); }
  bool has_ring() const { return !ring.empty(); }
};

/// An 8-bit image, row-major with interleaved channels (1 = gray, 3 = BGR).
struct Image {
  int width = 0;     ///< [px]
  int height = 0;    ///< [px]
  int channels = 1;  ///< 1 or 3
  std::vector<std::uint8_t> pixels;  ///< width * height * channels bytes

  Image() = default;
  Image(int width_px, int height_px, int channel_count = 1, std::uint8_t fill = 0)
      : width(width_px),
        height(height_px),
        channels(channel_count),
        pixels(static_cast<std::size_t>(width_px) * height_px * channel_count, fill) {}

  bool empty() const { return pixels.empty(); }
  std::uint8_t& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
  std::uint8_t at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }

 private:
  std::size_t index(int x, int y, int c) const {
    return (static_cast<std::size_t>(y) * width + x) * channels + c;
  }
};

}  // namespace l2s
