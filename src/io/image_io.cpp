// Images through OpenCV, converted to the library's 8-bit gray or BGR Image.
#include <l2s/io/image_io.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstring>
#include <filesystem>

namespace l2s::io {
namespace {

cv::Mat wrap(const Image& image) {
  const int type = CV_8UC(image.channels);
  return cv::Mat(image.height, image.width, type, const_cast<std::uint8_t*>(image.pixels.data()));
}

Image copy_of(const cv::Mat& mat) {
  Image image(mat.cols, mat.rows, mat.channels());
  const cv::Mat continuous = mat.isContinuous() ? mat : mat.clone();
  std::memcpy(image.pixels.data(), continuous.data, image.pixels.size());
  return image;
}

void check_layout(const Image& image, const std::string& what) {
  if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    throw ParamError(what, "image must be width x height x (1 or 3) bytes, got " +
                               std::to_string(image.width) + "x" + std::to_string(image.height) +
                               "x" + std::to_string(image.channels) + " with " +
                               std::to_string(image.pixels.size()) + " bytes");
}

}  // namespace

Image read_image(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw FileError(path, "missing file");
  cv::Mat mat;
  try {
    mat = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw FileError(path, std::string("cannot decode image: ") + e.what());
  }
  if (mat.empty()) throw FileError(path, "cannot decode image (corrupt or unknown format)");

  // 16-bit images keep their full range: 65535 maps to 255.
  if (mat.depth() == CV_16U) mat.convertTo(mat, CV_8U, 255.0 / 65535.0);
  if (mat.depth() != CV_8U)
    throw FileError(path, "unsupported pixel type (expected 8 or 16 bits unsigned)");
  switch (mat.channels()) {
    case 1:
      break;
    case 2:
      cv::extractChannel(mat, mat, 0);
      break;  // gray + alpha
    case 3:
      break;
    case 4:
      cv::cvtColor(mat, mat, cv::COLOR_BGRA2BGR);
      break;
    default:
      throw FileError(path, "unsupported channel count " + std::to_string(mat.channels()));
  }
  return copy_of(mat);
}

void write_png(const std::string& path, const Image& image, int compression) {
  check_layout(image, "image");
  if (compression < 0 || compression > 9) throw ParamError("compression", "must be in 0..9");
  std::vector<std::uint8_t> bytes;
  try {
    if (!cv::imencode(".png", wrap(image), bytes, {cv::IMWRITE_PNG_COMPRESSION, compression}))
      throw FileError(path, "PNG encoding failed");
  } catch (const cv::Exception& e) {
    throw FileError(path, std::string("PNG encoding failed: ") + e.what());
  }
  detail::write_file_atomically(path, std::string(bytes.begin(), bytes.end()));
}

Image to_gray(const Image& image) {
  if (image.channels == 1) return image;
  check_layout(image, "image");
  cv::Mat gray;
  cv::cvtColor(wrap(image), gray, cv::COLOR_BGR2GRAY);
  return copy_of(gray);
}

}  // namespace l2s::io
