#pragma once
// Private bridge between l2s::Image and OpenCV for the camera stages.

#include <l2s/error.hpp>
#include <l2s/types.hpp>

#include "detail/input_checks.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <string>

namespace l2s::detail {

/// The image's pixels as a cv::Mat view (CV_8UC1 gray or CV_8UC3 BGR), no copy.
/// Throws InputError("<name> image", ...) for an unusable image.
inline cv::Mat pixel_mat(const Image& image, const std::string& name) {
  check_image(image, name);
  return cv::Mat(image.height, image.width, image.channels == 1 ? CV_8UC1 : CV_8UC3,
                 const_cast<std::uint8_t*>(image.pixels.data()));
}

/// The 8-bit gray version of an image as a cv::Mat (a view when already gray).
/// Throws InputError("<name> image", ...) for an unusable image.
inline cv::Mat gray_mat(const Image& image, const std::string& name) {
  check_image(image, name);
  cv::Mat view(image.height, image.width, image.channels == 1 ? CV_8UC1 : CV_8UC3,
               const_cast<std::uint8_t*>(image.pixels.data()));
  if (image.channels == 1) return view;
  cv::Mat gray;
  cv::cvtColor(view, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

/// Bilinear gray value of an 8-bit gray image; the caller keeps (x, y) one
/// pixel inside it.
inline double gray_at(const cv::Mat& image, double x, double y) {
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  const double fx = x - ix, fy = y - iy;
  const std::uint8_t* r0 = image.ptr<std::uint8_t>(iy) + ix;
  const std::uint8_t* r1 = image.ptr<std::uint8_t>(iy + 1) + ix;
  return (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
}

}  // namespace l2s::detail
