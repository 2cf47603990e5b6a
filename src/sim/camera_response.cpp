// Vignetting follows the usual radial falloff model 1 - a (r / r_corner)^2
// around the principal point; blur is a Gaussian point spread (OpenCV's
// GaussianBlur, reflected border) on linear light, as a lens blurs radiance.

#include "sim/camera_response.hpp"

#include "sim/parallel.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {

void apply_camera_response(const Appearance& look, const Eigen::Vector2d& principal_point,
                           int threads, CleanImage* image) {
  const int W = image->width, H = image->height, C = image->channels;
  const bool gain = look.exposure != 1.0 || look.vignetting > 0.0;
  if (gain) {
    // Normalised by the farthest image corner from the principal point.
    const double du = std::max(principal_point.x() + 0.5, W - 0.5 - principal_point.x());
    const double dv = std::max(principal_point.y() + 0.5, H - 0.5 - principal_point.y());
    const double inv_corner2 = 1.0 / (du * du + dv * dv);
    parallel_for(H, threads, [&](int v) {
      float* row = image->intensity.data() + static_cast<std::size_t>(v) * W * C;
      const double y = v - principal_point.y();
      for (int u = 0; u < W; ++u) {
        const double x = u - principal_point.x();
        const double factor = look.exposure * (1.0 - look.vignetting * (x * x + y * y) * inv_corner2);
        for (int c = 0; c < C; ++c) row[u * C + c] = static_cast<float>(row[u * C + c] * factor);
      }
    });
  }
  if (look.blur_sigma > 0.0) {
    cv::Mat mat(H, W, CV_32FC(C), image->intensity.data());
    cv::Mat blurred;
    cv::GaussianBlur(mat, blurred, cv::Size(0, 0), look.blur_sigma, look.blur_sigma, cv::BORDER_REFLECT_101);
    blurred.copyTo(mat);  // same size and type: writes into the image's own buffer
  }
  if (look.gamma != 1.0) {
    // Single precision: 8-bit output needs far less, and powf is several times faster.
    const auto exponent = static_cast<float>(1.0 / look.gamma);
    parallel_for(H, threads, [&](int v) {
      float* row = image->intensity.data() + static_cast<std::size_t>(v) * W * C;
      for (int i = 0; i < W * C; ++i) row[i] = std::pow(std::max(0.0f, row[i]), exponent);
    });
  }
}

}  // namespace l2s::sim::detail
