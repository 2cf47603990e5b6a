#pragma once
// Private bridge between l2s::Image and OpenCV for the camera stages.

#include <l2s/error.hpp>
#include <l2s/types.hpp>

#include "detail/input_checks.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

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

}  // namespace l2s::detail
