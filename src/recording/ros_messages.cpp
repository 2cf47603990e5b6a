// sensor_msgs/Image: header, height, width, encoding, is_bigendian, step,
// data. sensor_msgs/CompressedImage: header, format, data.
// sensor_msgs/CameraInfo: header, height, width, distortion_model, D[],
// K[9], R[9], P[12], binning, roi.
#include <l2s/recording/ros_messages.hpp>

#include <l2s/error.hpp>

#include "recording/ros_header.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstring>
#include <limits>
#include <map>

namespace l2s {
namespace {

using detail::ByteReader;

Image to_image(const cv::Mat& mat) {
  Image image(mat.cols, mat.rows, mat.channels());
  for (int row = 0; row < mat.rows; ++row)
    std::memcpy(image.pixels.data() + static_cast<std::size_t>(row) * mat.cols * mat.channels(), mat.ptr(row),
                static_cast<std::size_t>(mat.cols) * mat.channels());
  return image;
}

/// Any 8- or 16-bit, 1/3/4-channel picture as 8-bit gray or BGR (16 bits
/// scaled by 1/256, alpha dropped). `rgb`: the channels are R, G, B.
Image eight_bit(cv::Mat mat, bool rgb) {
  if (mat.depth() == CV_16U) mat.convertTo(mat, CV_8U, 1.0 / 256.0);
  cv::Mat out;
  if (mat.channels() == 4)
    cv::cvtColor(mat, out, rgb ? cv::COLOR_RGBA2BGR : cv::COLOR_BGRA2BGR);
  else if (mat.channels() == 3 && rgb)
    cv::cvtColor(mat, out, cv::COLOR_RGB2BGR);
  else
    out = mat;
  return to_image(out);
}

struct Encoding {
  int type;        ///< OpenCV type of the data
  bool rgb;        ///< channels in R, G, B order
  int bayer = -1;  ///< OpenCV's demosaicing code, or -1
};

/// ROS's encodings. OpenCV names a Bayer pattern by the second row's second
/// and third pixels, ROS by the first row's first two: rggb is OpenCV's BG.
const std::map<std::string, Encoding>& encodings() {
  static const std::map<std::string, Encoding> table = {
      {"mono8", {CV_8UC1, false}},   {"8UC1", {CV_8UC1, false}},  {"mono16", {CV_16UC1, false}},
      {"16UC1", {CV_16UC1, false}},  {"bgr8", {CV_8UC3, false}},  {"8UC3", {CV_8UC3, false}},
      {"rgb8", {CV_8UC3, true}},     {"bgra8", {CV_8UC4, false}}, {"rgba8", {CV_8UC4, true}},
      {"bgr16", {CV_16UC3, false}},  {"rgb16", {CV_16UC3, true}},
      {"bayer_rggb8", {CV_8UC1, false, cv::COLOR_BayerBG2BGR}},
      {"bayer_bggr8", {CV_8UC1, false, cv::COLOR_BayerRG2BGR}},
      {"bayer_gbrg8", {CV_8UC1, false, cv::COLOR_BayerGR2BGR}},
      {"bayer_grbg8", {CV_8UC1, false, cv::COLOR_BayerGB2BGR}},
  };
  return table;
}

/// Why a png or jpeg stream is refused before decoding, or "": its header
/// states more pixels than any camera a calibration uses delivers (a
/// corrupt header would otherwise allocate gigabytes).
std::string too_large(const std::vector<std::uint8_t>& bytes) {
  constexpr std::uint64_t kMaxPixels = std::uint64_t{64} << 20;
  std::uint64_t width = 0, height = 0;
  const auto big16 = [&](std::size_t at) { return std::uint64_t{bytes[at]} << 8 | bytes[at + 1]; };
  const auto big32 = [&](std::size_t at) { return big16(at) << 16 | big16(at + 2); };
  if (bytes.size() >= 24 && bytes[0] == 0x89 && bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G') {
    width = big32(16), height = big32(20);  // IHDR, the first chunk
  } else if (bytes.size() >= 4 && bytes[0] == 0xFF && bytes[1] == 0xD8) {
    // JPEG markers up to the first start-of-frame (SOF0..SOF15 but DHT, JPG, DAC).
    for (std::size_t at = 2; at + 9 < bytes.size();) {
      if (bytes[at] != 0xFF) break;
      const std::uint8_t marker = bytes[at + 1];
      if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
        height = big16(at + 5), width = big16(at + 7);
        break;
      }
      at += 2 + big16(at + 2);
    }
  }
  if (width * height <= kMaxPixels) return "";
  return "its header states " + std::to_string(width) + "x" + std::to_string(height) + " px, more than " +
         std::to_string(kMaxPixels >> 20) + " megapixels";
}

}  // namespace

std::int64_t header_stamp_ns(const std::vector<std::uint8_t>& message) {
  try {
    ByteReader reader(message.data(), message.size());
    return detail::read_ros_header(reader).stamp_ns;
  } catch (const detail::ShortBuffer& e) {
    throw InputError("message header", std::string("cut short: ") + e.what());
  }
}

RecordedImage decode_image(const std::vector<std::uint8_t>& message) {
  const char* const input = "Image message";
  RecordedImage out;
  std::uint32_t height = 0, width = 0, step = 0, size = 0;
  bool big_endian = false;
  const std::uint8_t* data = nullptr;
  try {
    ByteReader reader(message.data(), message.size());
    const detail::RosHeader header = detail::read_ros_header(reader);
    out.stamp_ns = header.stamp_ns;
    out.frame_id = header.frame_id;
    height = reader.read<std::uint32_t>();
    width = reader.read<std::uint32_t>();
    out.encoding = reader.read_string();
    big_endian = reader.read<std::uint8_t>() != 0;
    step = reader.read<std::uint32_t>();
    size = reader.read<std::uint32_t>();
    data = reader.take(size, "the pixel data");
  } catch (const detail::ShortBuffer& e) {
    throw InputError(input, std::string("cut short: ") + e.what());
  }
  const auto found = encodings().find(out.encoding);
  if (found == encodings().end())
    throw InputError(input, "encoding '" + out.encoding + "' is not one of mono8, mono16, bgr8, rgb8, bgra8, rgba8, "
                            "bgr16, rgb16, 8UC1, 8UC3, 16UC1, bayer_{rggb,bggr,gbrg,grbg}8");
  const Encoding& encoding = found->second;
  if (height == 0 || width == 0) throw InputError(input, "an image of " + std::to_string(width) + "x" + std::to_string(height) + " px");
  const std::uint64_t row_bytes = static_cast<std::uint64_t>(width) * CV_ELEM_SIZE(encoding.type);
  if (step < row_bytes)
    throw InputError(input, "a step of " + std::to_string(step) + " bytes is shorter than a row of " +
                                std::to_string(width) + " px in " + out.encoding);
  if (static_cast<std::uint64_t>(step) * height > size)
    throw InputError(input, "holds " + std::to_string(size) + " data bytes, fewer than " + std::to_string(height) +
                                " rows of " + std::to_string(step));
  if (static_cast<std::uint64_t>(width) > std::numeric_limits<int>::max() ||
      static_cast<std::uint64_t>(height) > std::numeric_limits<int>::max())
    throw InputError(input, "an image of " + std::to_string(width) + "x" + std::to_string(height) + " px");
  cv::Mat mat(static_cast<int>(height), static_cast<int>(width), encoding.type, const_cast<std::uint8_t*>(data), step);
  mat = mat.clone();
  if (big_endian && mat.depth() == CV_16U) {
    for (int row = 0; row < mat.rows; ++row) {
      auto* p = mat.ptr<std::uint16_t>(row);
      for (int k = 0; k < mat.cols * mat.channels(); ++k) p[k] = static_cast<std::uint16_t>((p[k] >> 8) | (p[k] << 8));
    }
  }
  try {
    if (encoding.bayer >= 0) {
      cv::Mat colour;
      cv::cvtColor(mat, colour, encoding.bayer);
      out.image = to_image(colour);
    } else {
      out.image = eight_bit(mat, encoding.rgb);
    }
  } catch (const cv::Exception& e) {
    throw InputError(input, "a " + std::to_string(width) + "x" + std::to_string(height) + " px " + out.encoding +
                                " image that does not convert: " + e.err);
  }
  return out;
}

RecordedImage decode_compressed_image(const std::vector<std::uint8_t>& message) {
  const char* const input = "CompressedImage message";
  RecordedImage out;
  std::vector<std::uint8_t> bytes;
  try {
    ByteReader reader(message.data(), message.size());
    const detail::RosHeader header = detail::read_ros_header(reader);
    out.stamp_ns = header.stamp_ns;
    out.frame_id = header.frame_id;
    out.encoding = reader.read_string();
    const auto size = reader.read<std::uint32_t>();
    const std::uint8_t* data = reader.take(size, "the compressed data");
    bytes.assign(data, data + size);
  } catch (const detail::ShortBuffer& e) {
    throw InputError(input, std::string("cut short: ") + e.what());
  }
  if (const std::string why = too_large(bytes); !why.empty()) throw InputError(input, why);
  cv::Mat mat;
  try {
    mat = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw InputError(input, "its " + std::to_string(bytes.size()) + " bytes (format '" + out.encoding +
                                "') do not decode: " + e.err);
  }
  if (mat.empty())
    throw InputError(input, "its " + std::to_string(bytes.size()) + " bytes (format '" + out.encoding +
                                "') do not decode as an image");
  out.image = eight_bit(mat, false);  // OpenCV decodes to BGR order
  return out;
}

RecordedCameraInfo decode_camera_info(const std::vector<std::uint8_t>& message) {
  const char* const input = "CameraInfo message";
  RecordedCameraInfo out;
  CameraInfo& c = out.camera;
  try {
    ByteReader reader(message.data(), message.size());
    const detail::RosHeader header = detail::read_ros_header(reader);
    out.stamp_ns = header.stamp_ns;
    out.frame_id = header.frame_id;
    c.camera_name = header.frame_id;
    c.height = static_cast<int>(reader.read<std::uint32_t>());
    c.width = static_cast<int>(reader.read<std::uint32_t>());
    c.distortion_model = reader.read_string();
    const auto coefficients = reader.read<std::uint32_t>();
    if (coefficients > reader.remaining() / 8)
      throw InputError(input, "declares " + std::to_string(coefficients) + " distortion coefficients, more than its bytes hold");
    c.distortion_coefficients.resize(coefficients);
    for (double& d : c.distortion_coefficients) d = reader.read<double>();
    for (int k = 0; k < 9; ++k) c.camera_matrix(k / 3, k % 3) = reader.read<double>();
    for (int k = 0; k < 9; ++k) c.rectification_matrix(k / 3, k % 3) = reader.read<double>();
    for (int k = 0; k < 12; ++k) c.projection_matrix(k / 4, k % 4) = reader.read<double>();
    // binning and region of interest follow; the dataset's camera model has no place for them.
  } catch (const detail::ShortBuffer& e) {
    throw InputError(input, std::string("cut short: ") + e.what());
  }
  if (c.width <= 0 || c.height <= 0)
    throw InputError(input, "a camera of " + std::to_string(c.width) + "x" + std::to_string(c.height) + " px");
  if (!(c.fx() > 0.0) || !(c.fy() > 0.0))
    throw InputError(input, "a projection matrix P with no positive focal length (an uncalibrated camera)");
  return out;
}

}  // namespace l2s
