#include "io/pcd_header.hpp"

#include <l2s/error.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <limits>
#include <map>
#include <sstream>

namespace l2s::io::pcd {
namespace {

using Tokens = std::vector<std::string>;

Tokens split(const std::string& line) {
  Tokens tokens;
  std::istringstream stream(line);
  for (std::string token; stream >> token;) tokens.push_back(token);
  return tokens;
}

std::string upper(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return text;
}

std::uint64_t to_count(const std::string& token, const std::string& key, const std::string& path) {
  std::uint64_t value = 0;
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  if (result.ec != std::errc() || result.ptr != token.data() + token.size())
    throw FileError(path,
                    "PCD header: " + key + " value '" + token + "' is not a non-negative integer");
  return value;
}

const Tokens& values_of(const std::map<std::string, Tokens>& keys, const std::string& key,
                        std::size_t expected, const std::string& path) {
  const auto it = keys.find(key);
  if (it == keys.end()) throw FileError(path, "PCD header: missing " + key);
  if (it->second.size() != expected)
    throw FileError(path, "PCD header: " + key + " has " + std::to_string(it->second.size()) +
                              " entries for " + std::to_string(expected) + " fields");
  return it->second;
}

std::uint64_t single(const std::map<std::string, Tokens>& keys, const std::string& key,
                     const std::string& path) {
  const Tokens& tokens = keys.at(key);
  if (tokens.size() != 1) throw FileError(path, "PCD header: " + key + " needs one value");
  return to_count(tokens[0], key, path);
}

bool valid_type(char type, int size) {
  if (type == 'F') return size == 4 || size == 8;
  if (type == 'I' || type == 'U') return size == 1 || size == 2 || size == 4 || size == 8;
  return false;
}

// Splits the header into key -> values up to and including DATA; returns the
// position of the first data byte.
std::size_t read_keys(const std::string& bytes, const std::string& path,
                      std::map<std::string, Tokens>& keys) {
  std::size_t position = 0;
  while (position < bytes.size()) {
    std::size_t end = bytes.find('\n', position);
    const std::size_t next = end == std::string::npos ? bytes.size() : end + 1;
    if (end == std::string::npos) end = bytes.size();
    const Tokens tokens = split(bytes.substr(position, end - position));
    position = next;
    if (tokens.empty() || tokens[0][0] == '#') continue;
    std::string key = upper(tokens[0]);
    if (key == "COLUMNS") key = "FIELDS";  // the v0.5 name
    keys[key] = Tokens(tokens.begin() + 1, tokens.end());
    if (key == "DATA") return position;
  }
  throw FileError(path, "not a PCD file (no DATA line in the header)");
}

}  // namespace

int Header::find(std::initializer_list<const char*> names) const {
  for (const char* name : names)
    for (std::size_t i = 0; i < fields.size(); ++i)
      if (fields[i].name == name) return static_cast<int>(i);
  return -1;
}

Header parse_header(const std::string& bytes, const std::string& path) {
  std::map<std::string, Tokens> keys;
  Header header;
  header.data_offset = read_keys(bytes, path, keys);

  const auto fields = keys.find("FIELDS");
  if (fields == keys.end() || fields->second.empty())
    throw FileError(path, "PCD header: missing or empty FIELDS");
  const std::size_t n = fields->second.size();
  const Tokens& sizes = values_of(keys, "SIZE", n, path);
  // v0.6 files may leave out TYPE (all float) and COUNT (all 1).
  const Tokens types = keys.count("TYPE") ? values_of(keys, "TYPE", n, path) : Tokens(n, "F");
  const Tokens counts = keys.count("COUNT") ? values_of(keys, "COUNT", n, path) : Tokens(n, "1");

  for (std::size_t i = 0; i < n; ++i) {
    Field field;
    field.name = fields->second[i];
    const std::uint64_t size = to_count(sizes[i], "SIZE", path);
    field.size = static_cast<int>(std::min<std::uint64_t>(size, 16));
    field.type = types[i].size() == 1 ? static_cast<char>(std::toupper(types[i][0])) : '?';
    if (!valid_type(field.type, field.size) || size != static_cast<std::uint64_t>(field.size))
      throw FileError(path, "PCD header: field " + field.name + " has TYPE " + types[i] + " SIZE " +
                                sizes[i] + ", not a number type");
    field.count = to_count(counts[i], "COUNT", path);
    // Bounded so that sums of field bytes cannot overflow.
    if (field.count == 0 || field.count > (1u << 24))
      throw FileError(path, "PCD header: field " + field.name + " has COUNT " + counts[i]);
    field.offset = header.point_size;
    header.point_size += field.bytes();
    header.fields.push_back(field);
  }

  const bool has_width = keys.count("WIDTH"), has_points = keys.count("POINTS");
  if (!has_width && !has_points) throw FileError(path, "PCD header: missing WIDTH and POINTS");
  header.height = keys.count("HEIGHT") ? single(keys, "HEIGHT", path) : 1;
  if (has_points) header.points = single(keys, "POINTS", path);
  header.width = has_width ? single(keys, "WIDTH", path) : header.points;
  const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
  if (header.height != 0 && header.width > max / header.height)
    throw FileError(path, "PCD header: WIDTH * HEIGHT overflows");
  if (!has_points) header.points = header.width * header.height;
  if (header.points != header.width * header.height)
    throw FileError(path, "PCD header: POINTS " + std::to_string(header.points) +
                              " != WIDTH * HEIGHT (" + std::to_string(header.width) + " * " +
                              std::to_string(header.height) + ")");

  const Tokens& data = keys.at("DATA");
  std::string encoding = data.empty() ? "" : data[0];
  std::transform(encoding.begin(), encoding.end(), encoding.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (encoding == "ascii")
    header.encoding = Encoding::Ascii;
  else if (encoding == "binary")
    header.encoding = Encoding::Binary;
  else if (encoding == "binary_compressed")
    header.encoding = Encoding::BinaryCompressed;
  else
    throw FileError(
        path, "PCD header: DATA '" + encoding + "' is not ascii, binary or binary_compressed");
  return header;
}

}  // namespace l2s::io::pcd
