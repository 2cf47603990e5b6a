// PCD v0.7 writer: x y z (F4), then intensity (F4) and ring (U2) when the cloud
// has them, as one unorganized row (WIDTH = N, HEIGHT = 1) or as HEIGHT rows of
// WIDTH = N / HEIGHT points (organised, e.g. one row per laser). binary_compressed
// follows PCL's layout: the fields as separate arrays, LZF-compressed, behind
// two uint32 sizes (compressed, uncompressed).
#include <l2s/io/pcd.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"
#include "io/lzf.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace l2s::io {
namespace {

const char* encoding_name(PcdEncoding encoding) {
  switch (encoding) {
    case PcdEncoding::Ascii:
      return "ascii";
    case PcdEncoding::Binary:
      return "binary";
    default:
      return "binary_compressed";
  }
}

std::string header(const LidarCloud& cloud, PcdEncoding encoding, std::size_t height) {
  const bool i = cloud.has_intensity(), r = cloud.has_ring();
  std::ostringstream out;
  out << "# .PCD v0.7 - Point Cloud Data file format\n"
      << "VERSION 0.7\n"
      << "FIELDS x y z" << (i ? " intensity" : "") << (r ? " ring" : "") << "\n"
      << "SIZE 4 4 4" << (i ? " 4" : "") << (r ? " 2" : "") << "\n"
      << "TYPE F F F" << (i ? " F" : "") << (r ? " U" : "") << "\n"
      << "COUNT 1 1 1" << (i ? " 1" : "") << (r ? " 1" : "") << "\n"
      << "WIDTH " << cloud.size() / height << "\n"
      << "HEIGHT " << height << "\n"
      << "VIEWPOINT 0 0 0 1 0 0 0\n"
      << "POINTS " << cloud.size() << "\n"
      << "DATA " << encoding_name(encoding) << "\n";
  return out.str();
}

template <typename T>
void append(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

// Shortest text that reads back as the same float; NaN in the spelling PCL reads.
void append_text(std::string& text, float value) {
  if (std::isnan(value)) {
    text += "nan";
    return;
  }
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  text.append(buffer, result.ptr);
}

std::string ascii_data(const LidarCloud& cloud) {
  std::string text;
  text.reserve(cloud.size() * 40);
  for (std::size_t k = 0; k < cloud.size(); ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      if (axis > 0) text += ' ';
      append_text(text, static_cast<float>(cloud.points[k][axis]));
    }
    if (cloud.has_intensity()) text += ' ', append_text(text, cloud.intensity[k]);
    if (cloud.has_ring()) text += ' ', text += std::to_string(cloud.ring[k]);
    text += '\n';
  }
  return text;
}

std::string binary_data(const LidarCloud& cloud) {
  std::string bytes;
  bytes.reserve(cloud.size() * 18);
  for (std::size_t k = 0; k < cloud.size(); ++k) {
    for (int axis = 0; axis < 3; ++axis) append(bytes, static_cast<float>(cloud.points[k][axis]));
    if (cloud.has_intensity()) append(bytes, cloud.intensity[k]);
    if (cloud.has_ring()) append(bytes, cloud.ring[k]);
  }
  return bytes;
}

std::string compressed_data(const LidarCloud& cloud, const std::string& path) {
  std::string arrays;  // structure of arrays: all x, all y, all z, ...
  arrays.reserve(cloud.size() * 18);
  for (int axis = 0; axis < 3; ++axis)
    for (const auto& p : cloud.points) append(arrays, static_cast<float>(p[axis]));
  for (float value : cloud.intensity) append(arrays, value);
  for (std::uint16_t value : cloud.ring) append(arrays, value);
  if (arrays.size() > std::numeric_limits<std::uint32_t>::max())
    throw FileError(path, "cloud too large for binary_compressed (4 GiB limit of the format)");
  const auto compressed =
      lzf::compress(reinterpret_cast<const std::uint8_t*>(arrays.data()), arrays.size());
  std::string bytes;
  append(bytes, static_cast<std::uint32_t>(compressed.size()));
  append(bytes, static_cast<std::uint32_t>(arrays.size()));
  bytes.append(reinterpret_cast<const char*>(compressed.data()), compressed.size());
  return bytes;
}

}  // namespace

void write_pcd(const std::string& path, const LidarCloud& cloud, PcdEncoding encoding,
               std::size_t height) {
  if (height == 0 || cloud.size() % height != 0)
    throw ParamError("height", std::to_string(height) + " rows cannot hold " +
                                   std::to_string(cloud.size()) + " points (" + path + ")");
  if (cloud.has_intensity() && cloud.intensity.size() != cloud.size())
    throw ParamError("cloud.intensity", std::to_string(cloud.intensity.size()) + " values for " +
                                            std::to_string(cloud.size()) + " points (" + path +
                                            ")");
  if (cloud.has_ring() && cloud.ring.size() != cloud.size())
    throw ParamError("cloud.ring", std::to_string(cloud.ring.size()) + " values for " +
                                       std::to_string(cloud.size()) + " points (" + path + ")");
  std::string content = header(cloud, encoding, height);
  switch (encoding) {
    case PcdEncoding::Ascii:
      content += ascii_data(cloud);
      break;
    case PcdEncoding::Binary:
      content += binary_data(cloud);
      break;
    default:
      content += compressed_data(cloud, path);
      break;
  }
  detail::write_file_atomically(path, content);
}

}  // namespace l2s::io
