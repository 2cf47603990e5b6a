// The corner precision of the markers in one image (marker_corner_noise.hpp).

#include "camera/marker_corner_noise.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

/// Bilinear gray level at (x, y), or NaN outside the image.
double gray_at(const cv::Mat& gray, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= gray.cols || y0 + 1 >= gray.rows) return std::nan("");
  const double fx = x - x0, fy = y - y0;
  const auto p = [&](int dx, int dy) { return static_cast<double>(gray.at<std::uint8_t>(y0 + dy, x0 + dx)); };
  return (1 - fy) * ((1 - fx) * p(0, 0) + fx * p(1, 0)) + fy * ((1 - fx) * p(0, 1) + fx * p(1, 1));
}

/// Where along the normal through `at` the gray level steps most, within
/// +-reach px, to sub-pixel (a parabola through the largest difference and
/// its neighbours); NaN when the step lies at the window's end.
double step_offset(const cv::Mat& gray, const Eigen::Vector2d& at, const Eigen::Vector2d& normal, double reach) {
  constexpr double kStep = 0.25;  // [px] between samples along the normal
  const int half = static_cast<int>(std::floor(reach / kStep));
  std::vector<double> steps;
  for (int i = -half; i < half; ++i) {
    const Eigen::Vector2d a = at + normal * (i * kStep), b = at + normal * ((i + 1) * kStep);
    const double d = gray_at(gray, b.x(), b.y()) - gray_at(gray, a.x(), a.y());
    if (!std::isfinite(d)) return std::nan("");
    steps.push_back(std::abs(d));
  }
  const auto peak = std::max_element(steps.begin(), steps.end());
  const std::size_t k = static_cast<std::size_t>(peak - steps.begin());
  if (k == 0 || k + 1 >= steps.size()) return std::nan("");
  const double l = steps[k - 1], c = steps[k], r = steps[k + 1];
  const double denominator = l - 2.0 * c + r;
  const double shift = denominator < 0.0 ? 0.5 * (l - r) / denominator : 0.0;
  return (static_cast<double>(k) - half + 0.5 + shift) * kStep;
}

}  // namespace

double marker_corner_sigma(const cv::Mat& gray, const std::vector<MonoBoardDetector::Marker>& markers, int bits) {
  double squares = 0.0, dof = 0.0, samples = 0.0;
  int sides = 0;
  for (const auto& marker : markers) {
    for (std::size_t s = 0; s < 4; ++s) {
      const Eigen::Vector2d a = marker.corners_px[s], b = marker.corners_px[(s + 1) % 4];
      const double length = (b - a).norm();
      // The border cell's width bounds the search, so that the step found
      // is the quiet zone's, not one between the border and the bits.
      const double reach = std::min(3.0, 0.45 * length / (bits + 2));
      const int count = static_cast<int>(0.7 * length / 1.5);
      if (reach < 0.75 || count < 5) continue;
      const Eigen::Vector2d along = (b - a) / length, normal(-along.y(), along.x());
      std::vector<double> t, d;
      for (int i = 0; i < count; ++i) {
        const double f = 0.15 + 0.7 * (i + 0.5) / count;
        const double offset = step_offset(gray, a + f * (b - a), normal, reach);
        if (std::isfinite(offset)) t.push_back(f), d.push_back(offset);
      }
      if (t.size() < 5) continue;
      // A straight line through the offsets: the corners' own error tilts
      // and shifts it; what is left is the edge's scatter.
      const double n = static_cast<double>(t.size());
      double st = 0, sd = 0, stt = 0, std_ = 0;
      for (std::size_t i = 0; i < t.size(); ++i) st += t[i], sd += d[i], stt += t[i] * t[i], std_ += t[i] * d[i];
      const double slope = (n * std_ - st * sd) / (n * stt - st * st), intercept = (sd - slope * st) / n;
      for (std::size_t i = 0; i < t.size(); ++i) squares += std::pow(d[i] - intercept - slope * t[i], 2);
      dof += n - 2.0;
      samples += n;
      ++sides;
    }
  }
  if (sides == 0 || dof <= 0.0) return 0.0;
  const double edge_sigma = std::sqrt(squares / dof);
  return edge_sigma * std::sqrt(4.0 / (samples / sides));
}

}  // namespace l2s::detail
