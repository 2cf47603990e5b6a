// PCD v0.7 reader. Every size in the header is checked against the bytes the
// file really holds before anything is allocated, so a truncated or lying file
// ends in a FileError, never in a crash or a huge allocation.
#include <l2s/io/pcd.hpp>

#include <l2s/error.hpp>

#include "io/lzf.hpp"
#include "io/pcd_header.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "PCD binary data is little-endian; this reader assumes a little-endian host"
#endif

namespace l2s::io {
namespace {

using pcd::Field;
using pcd::Header;

std::string read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, "missing file or cannot open for reading");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw FileError(path, "read error");
  return bytes.str();
}

template <typename T>
double load_as(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return static_cast<double>(value);
}

double load(const std::uint8_t* p, const Field& field) {
  switch (field.type) {
    case 'F':
      return field.size == 4 ? load_as<float>(p) : load_as<double>(p);
    case 'I':
      switch (field.size) {
        case 1:
          return load_as<std::int8_t>(p);
        case 2:
          return load_as<std::int16_t>(p);
        case 4:
          return load_as<std::int32_t>(p);
        default:
          return load_as<std::int64_t>(p);
      }
    default:
      switch (field.size) {
        case 1:
          return load_as<std::uint8_t>(p);
        case 2:
          return load_as<std::uint16_t>(p);
        case 4:
          return load_as<std::uint32_t>(p);
        default:
          return load_as<std::uint64_t>(p);
      }
  }
}

// The fields the calibrator reads; -1 when absent.
struct Wanted {
  int x, y, z, intensity, ring;
  explicit Wanted(const Header& header)
      : x(header.find({"x"})),
        y(header.find({"y"})),
        z(header.find({"z"})),
        intensity(header.find({"intensity", "i"})),
        ring(header.find({"ring", "laser_id"})) {}
};

// Builds the cloud from value(field, point); shared by all three encodings.
template <typename Value>
LidarCloud assemble(const Header& header, const Wanted& wanted, const std::string& path,
                    Value&& value) {
  const auto n = static_cast<std::size_t>(header.points);
  LidarCloud cloud;
  cloud.points.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    cloud.points[i] = Eigen::Vector3d(value(wanted.x, i), value(wanted.y, i), value(wanted.z, i));
  if (wanted.intensity >= 0) {
    cloud.intensity.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      cloud.intensity[i] = static_cast<float>(value(wanted.intensity, i));
  }
  if (wanted.ring >= 0) {
    cloud.ring.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double ring = value(wanted.ring, i);
      if (!(ring >= 0.0 && ring <= 65535.0) || ring != std::floor(ring))
        throw FileError(path, "point " + std::to_string(i) + " has ring " + std::to_string(ring) +
                                  ", not a laser index in 0..65535");
      cloud.ring[i] = static_cast<std::uint16_t>(ring);
    }
  }
  return cloud;
}

LidarCloud decode_binary(const Header& header, const Wanted& wanted, const std::uint8_t* data,
                         std::size_t available, const std::string& path) {
  if (header.points > available / header.point_size)
    throw FileError(path, "truncated: " + std::to_string(header.points) + " points need " +
                              std::to_string(header.points * header.point_size) +
                              " bytes of binary data, the file has " + std::to_string(available));
  const auto value = [&](int f, std::size_t i) {
    const Field& field = header.fields[f];
    return load(data + i * header.point_size + field.offset, field);
  };
  return assemble(header, wanted, path, value);
}

std::uint32_t load_u32(const std::uint8_t* p) {
  std::uint32_t value;
  std::memcpy(&value, p, 4);
  return value;
}

LidarCloud decode_compressed(const Header& header, const Wanted& wanted, const std::uint8_t* data,
                             std::size_t available, const std::string& path) {
  // An empty cloud may end right after the header.
  if (header.points == 0 && available < 8)
    return assemble(header, wanted, path, [](int, std::size_t) { return 0.0; });
  if (available < 8) throw FileError(path, "truncated: no binary_compressed size header");
  const std::uint32_t compressed = load_u32(data);
  const std::uint32_t uncompressed = load_u32(data + 4);
  if (compressed > available - 8)
    throw FileError(path, "truncated: compressed size " + std::to_string(compressed) +
                              " bytes, the file has " + std::to_string(available - 8));
  if (header.points > std::uint64_t{uncompressed} / header.point_size ||
      header.points * header.point_size != uncompressed)
    throw FileError(path, "compressed data holds " + std::to_string(uncompressed) + " bytes, " +
                              std::to_string(header.points) + " points need " +
                              std::to_string(header.points * header.point_size));
  if (uncompressed > lzf::max_decompressed_size(compressed))
    throw FileError(path, "corrupt: " + std::to_string(compressed) +
                              " compressed bytes cannot hold " + std::to_string(uncompressed));
  std::vector<std::uint8_t> raw(uncompressed);
  try {
    lzf::decompress(data + 8, compressed, raw.data(), raw.size());
  } catch (const lzf::Error& e) {
    throw FileError(path, std::string("corrupt compressed data: ") + e.what());
  }
  // Structure of arrays: all values of field 0, then all of field 1, ...
  std::vector<std::uint64_t> block(header.fields.size());
  for (std::size_t f = 1; f < block.size(); ++f)
    block[f] = block[f - 1] + header.fields[f - 1].bytes() * header.points;
  const auto value = [&](int f, std::size_t i) {
    const Field& field = header.fields[f];
    return load(raw.data() + block[f] + i * field.bytes(), field);
  };
  return assemble(header, wanted, path, value);
}

double parse_token(const std::string_view token, const Field& field, bool& ok) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  if (begin != end && *begin == '+') ++begin;  // from_chars rejects a leading '+'
  if (field.type == 'F' && field.size == 4) {
    float value = 0.0f;  // parsed as float so that F4 values match their binary twin
    const auto r = std::from_chars(begin, end, value);
    ok = r.ec == std::errc() && r.ptr == end;
    return value;
  }
  if (field.type != 'F') {
    long long value = 0;
    const auto r = std::from_chars(begin, end, value);
    if (r.ec == std::errc() && r.ptr == end) return ok = true, static_cast<double>(value);
  }
  double value = 0.0;
  const auto r = std::from_chars(begin, end, value);
  ok = r.ec == std::errc() && r.ptr == end;
  return value;
}

LidarCloud decode_ascii(const Header& header, const Wanted& wanted, const std::string& bytes,
                        const std::string& path) {
  std::uint64_t tokens_per_point = 0;
  std::vector<std::uint64_t> first_token(header.fields.size());
  for (std::size_t f = 0; f < header.fields.size(); ++f) {
    first_token[f] = tokens_per_point;
    tokens_per_point += header.fields[f].count;
  }
  // Every point takes at least one byte per value: bound the allocation by the file.
  const std::size_t available = bytes.size() - header.data_offset;
  if (header.points > available / tokens_per_point)
    throw FileError(path, "truncated: " + std::to_string(header.points) +
                              " ascii points cannot fit in " + std::to_string(available) +
                              " bytes");
  const auto n = static_cast<std::size_t>(header.points);
  const int wanted_fields[] = {wanted.x, wanted.y, wanted.z, wanted.intensity, wanted.ring};
  std::vector<std::vector<double>> values(header.fields.size());
  for (int f : wanted_fields)
    if (f >= 0) values[f].resize(n);

  std::size_t position = header.data_offset, point = 0, line_number = 0;
  std::vector<std::string_view> tokens;
  while (point < n && position < bytes.size()) {
    std::size_t end = bytes.find('\n', position);
    if (end == std::string::npos) end = bytes.size();
    const std::string_view line(bytes.data() + position, end - position);
    position = end + 1;
    ++line_number;
    tokens.clear();
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      const std::size_t start = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i > start) tokens.push_back(line.substr(start, i - start));
    }
    if (tokens.empty() || tokens[0][0] == '#') continue;
    if (tokens.size() != tokens_per_point)
      throw FileError(path, "ascii data line " + std::to_string(line_number) + " has " +
                                std::to_string(tokens.size()) + " values, expected " +
                                std::to_string(tokens_per_point));
    for (int f : wanted_fields) {
      if (f < 0) continue;
      bool ok = false;
      values[f][point] = parse_token(tokens[first_token[f]], header.fields[f], ok);
      if (!ok)
        throw FileError(path, "ascii data line " + std::to_string(line_number) + ": '" +
                                  std::string(tokens[first_token[f]]) +
                                  "' is not a number (field " + header.fields[f].name + ")");
    }
    ++point;
  }
  if (point < n)
    throw FileError(path, "truncated: " + std::to_string(point) + " of " + std::to_string(n) +
                              " ascii points present");
  return assemble(header, wanted, path, [&](int f, std::size_t i) { return values[f][i]; });
}

}  // namespace

LidarCloud read_pcd(const std::string& path) { return read_pcd_file(path).cloud; }

PcdFile read_pcd_file(const std::string& path) {
  const std::string bytes = read_whole_file(path);
  const Header header = pcd::parse_header(bytes, path);
  const Wanted wanted(header);
  const std::pair<int, const char*> required[] = {
      {wanted.x, "x"}, {wanted.y, "y"}, {wanted.z, "z"}};
  for (const auto& [index, name] : required)
    if (index < 0) throw FileError(path, std::string("no field ") + name + " (x y z are required)");

  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data()) + header.data_offset;
  const std::size_t available = bytes.size() - header.data_offset;
  PcdFile file;
  file.width = static_cast<std::size_t>(header.width);
  file.height = static_cast<std::size_t>(header.height);
  switch (header.encoding) {
    case pcd::Encoding::Ascii:
      file.cloud = decode_ascii(header, wanted, bytes, path);
      break;
    case pcd::Encoding::Binary:
      file.cloud = decode_binary(header, wanted, data, available, path);
      break;
    default:
      file.cloud = decode_compressed(header, wanted, data, available, path);
      break;
  }
  return file;
}

}  // namespace l2s::io
