#include "detail/input_checks.hpp"

#include <l2s/error.hpp>

#include <cmath>
#include <sstream>

namespace l2s::detail {
namespace {

std::string size_text(int width, int height) { return std::to_string(width) + "x" + std::to_string(height) + " px"; }

}  // namespace

void check_camera(const CameraInfo& camera, const std::string& name) {
  if (camera.width <= 0 || camera.height <= 0)
    throw ParamError(name + ".width", "image size " + size_text(camera.width, camera.height) + " must be positive");
  if (!camera.projection_matrix.allFinite())
    throw ParamError(name + ".projection_matrix", "must be finite");
  if (!(camera.fx() > 0.0) || !(camera.fy() > 0.0))
    throw ParamError(name + ".projection_matrix", "fx and fy must be positive");
}

namespace {

void check_size(const Image& image, const CameraInfo& camera, const std::string& name) {
  if (camera.width <= 0 || (image.width == camera.width && image.height == camera.height)) return;
  throw InputError(name + " image", size_text(image.width, image.height) + ", but the " + name + " camera is " +
                                        size_text(camera.width, camera.height));
}

}  // namespace

void check_cameras(const StereoCamera& cameras) {
  check_camera(cameras.left, "cameras.left");
  check_camera(cameras.right, "cameras.right");
  const double baseline = cameras.baseline();
  if (!(std::isfinite(baseline) && baseline > 0.0)) {
    std::ostringstream problem;
    problem << "baseline -P[0][3] / fx = " << baseline
            << " m must be positive (the right camera's P, or left and right swapped?)";
    throw ParamError("cameras.right.projection_matrix", problem.str());
  }
}

void check_image(const Image& image, const std::string& name) {
  const std::string input = name + " image";
  if (image.width <= 0 || image.height <= 0 || image.empty())
    throw InputError(input, "empty (" + size_text(image.width, image.height) + ", " +
                                std::to_string(image.pixels.size()) + " bytes)");
  if (image.channels != 1 && image.channels != 3)
    throw InputError(input, std::to_string(image.channels) + " channels; 1 (gray) or 3 (BGR) expected");
  const auto expected = static_cast<std::size_t>(image.width) * image.height * image.channels;
  if (image.pixels.size() != expected)
    throw InputError(input, std::to_string(image.pixels.size()) + " bytes of pixels for " +
                                size_text(image.width, image.height) + " x " + std::to_string(image.channels) +
                                " channels (" + std::to_string(expected) + ")");
}

void check_image(const Image& image, const CameraInfo& camera, const std::string& name) {
  check_image(image, name);
  check_size(image, camera, name);
}

void check_stereo_images(const Image& left, const Image& right, const StereoCamera& cameras) {
  check_image(left, "left");
  check_image(right, "right");
  check_size(left, cameras.left, "left");
  check_size(right, cameras.right, "right");
  if (left.width != right.width || left.height != right.height)
    throw InputError("right image", size_text(right.width, right.height) + ", but the left image is " +
                                        size_text(left.width, left.height));
}

}  // namespace l2s::detail
