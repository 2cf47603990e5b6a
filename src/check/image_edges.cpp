// Image edges for the calibration check: Canny on the rectified left image,
// then the Euclidean distance transform, so that scoring a projected lidar
// discontinuity is one lookup.

#include "check/image_edges.hpp"

#include "camera/cv_image.hpp"
#include "camera/noise_level.hpp"

#include <l2s/error.hpp>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace l2s::detail {
namespace {

cv::Mat to_mat(const Eigen::MatrixXd& m) {
  cv::Mat out(static_cast<int>(m.rows()), static_cast<int>(m.cols()), CV_64F);
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) out.at<double>(r, c) = m(r, c);
  return out;
}

/// The q-quantile of the squared Sobel magnitude over all pixels, exactly
/// (the value std::nth_element would put at rank q (n - 1)): a histogram of
/// coarse bins finds the bin holding that rank, then only that bin's values
/// are ranked (sorting a megapixel's values took most of this step's time).
std::int32_t squared_magnitude_quantile(const cv::Mat& dx, const cv::Mat& dy, double q) {
  constexpr int kShift = 10;                   // bins of 1024 squared levels
  constexpr std::int32_t kMaxSquared = 2 * 1020 * 1020;  // a 3x3 Sobel of 8-bit pixels reaches 4 * 255 per axis
  const auto squared = [](std::int16_t gx, std::int16_t gy) { return gx * gx + gy * gy; };
  if (dx.total() == 0) return 0;
  std::vector<std::size_t> histogram((kMaxSquared >> kShift) + 1, 0);
  for (int y = 0; y < dx.rows; ++y) {
    const std::int16_t *gx = dx.ptr<std::int16_t>(y), *gy = dy.ptr<std::int16_t>(y);
    for (int x = 0; x < dx.cols; ++x) ++histogram[static_cast<std::size_t>(squared(gx[x], gy[x]) >> kShift)];
  }
  auto rank = static_cast<std::size_t>(q * static_cast<double>(dx.total() - 1));
  std::size_t bin = 0;
  while (rank >= histogram[bin]) rank -= histogram[bin++];
  std::vector<std::int32_t> in_bin;
  in_bin.reserve(histogram[bin]);
  for (int y = 0; y < dx.rows; ++y) {
    const std::int16_t *gx = dx.ptr<std::int16_t>(y), *gy = dy.ptr<std::int16_t>(y);
    for (int x = 0; x < dx.cols; ++x) {
      const std::int32_t v = squared(gx[x], gy[x]);
      if (static_cast<std::size_t>(v >> kShift) == bin) in_bin.push_back(v);
    }
  }
  std::nth_element(in_bin.begin(), in_bin.begin() + static_cast<std::ptrdiff_t>(rank), in_bin.end());
  return in_bin[rank];
}

}  // namespace

cv::Mat rectified_left_gray(const Image& left, const StereoCamera& cameras) {
  const CameraInfo& info = cameras.left;
  if (left.width != info.width || left.height != info.height)
    throw ParamError("left", "image size differs from the left camera");
  cv::Mat gray = gray_mat(left, "left");
  if (cameras.images != ImageKind::Raw) return gray;
  const cv::Mat K = to_mat(info.camera_matrix), R = to_mat(info.rectification_matrix);
  const cv::Mat P = to_mat(info.projection_matrix.leftCols<3>());
  cv::Mat D(1, static_cast<int>(info.distortion_coefficients.size()), CV_64F);
  for (int i = 0; i < D.cols; ++i) D.at<double>(0, i) = info.distortion_coefficients[i];
  cv::Mat map_x, map_y;
  const cv::Size size(info.width, info.height);
  if (info.distortion_model == "equidistant")
    cv::fisheye::initUndistortRectifyMap(K, D.colRange(0, std::min(4, D.cols)), R, P, size, CV_32FC1, map_x, map_y);
  else
    cv::initUndistortRectifyMap(K, D, R, P, size, CV_32FC1, map_x, map_y);
  cv::Mat rectified;
  cv::remap(gray, rectified, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return rectified;
}

cv::Mat canny_edges(const cv::Mat& gray, const SceneObserver::Params& params) {
  // The gradients once, for the thresholds and for Canny itself (as Canny
  // would take them: 3x3 Sobel, borders replicated).
  cv::Mat dx, dy;
  cv::Sobel(gray, dx, CV_16S, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(gray, dy, CV_16S, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  // The strongest edges: the 99.9th percentile of the Sobel magnitude (the
  // board's outline and rims are about a thousandth of an image's pixels).
  // Ranked by the squared magnitude, an exact integer: one square root, not
  // one per pixel.
  const double strongest = std::sqrt(static_cast<float>(squared_magnitude_quantile(dx, dy, 0.999)));
  const double scale = std::clamp(strongest / params.strong_edge, 0.0, 1.0);
  // The noise floor: each 3x3 Sobel component of pure noise has a sigma of
  // sqrt(12) sigma = 3.46 sigma; the magnitude of noise exceeds 2.6 of those
  // (9 sigma) in 3 % of pixels, which hysteresis only follows from a real
  // edge, and 3.7 (13 sigma) in one pixel of a thousand, too few to seed
  // chains of their own.
  const double sigma = image_noise_sigma(gray);
  const double low = std::max(params.canny_low * scale, 9.0 * sigma);
  const double high = std::max({params.canny_high * scale, 13.0 * sigma, low});
  cv::Mat edges;
  cv::Canny(dx, dy, edges, low, high, true);
  return edges;
}

EdgeDistanceMap edge_distance_map(const cv::Mat& gray, const SceneObserver::Params& params) {
  const cv::Mat edges = canny_edges(gray, params);
  EdgeDistanceMap map;
  map.width = gray.cols;
  map.height = gray.rows;
  map.edge_pixels = static_cast<std::size_t>(cv::countNonZero(edges));
  // distanceTransform measures to the nearest zero pixel: edges must be zero.
  cv::Mat distance;
  cv::distanceTransform(255 - edges, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  map.distance.resize(static_cast<std::size_t>(map.width) * map.height);
  for (int y = 0; y < map.height; ++y) {
    const float* row = distance.ptr<float>(y);
    for (int x = 0; x < map.width; ++x) {
      // Rounded half up, as std::round for distances >= 0, without its call per pixel.
      const double steps = row[x] / map.unit;
      map.distance[static_cast<std::size_t>(y) * map.width + x] =
          steps >= 254.5 ? 255 : static_cast<std::uint8_t>(steps + 0.5);
    }
  }
  return map;
}

}  // namespace l2s::detail
