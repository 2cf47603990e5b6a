#pragma once
// The header of a PCD v0.7 file, parsed and checked against itself, so that the
// data decoders can trust every size in it.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace l2s::io::pcd {

struct Field {
  std::string name;
  char type = 'F';           ///< 'F' float, 'I' signed, 'U' unsigned
  int size = 4;              ///< [bytes] 1, 2, 4 or 8
  std::uint64_t count = 1;   ///< elements per point (x y z have 1; descriptors many)
  std::uint64_t offset = 0;  ///< [bytes] of the first element within one point record
  std::uint64_t bytes() const { return count * static_cast<std::uint64_t>(size); }
};

enum class Encoding { Ascii, Binary, BinaryCompressed };

struct Header {
  std::vector<Field> fields;
  std::uint64_t width = 0;
  std::uint64_t height = 1;
  std::uint64_t points = 0;
  Encoding encoding = Encoding::Ascii;
  std::uint64_t point_size = 0;  ///< [bytes] one point record: sum of the fields' bytes
  std::size_t data_offset = 0;   ///< position of the first byte after the DATA line

  /// Index of the first field named one of `names`, or -1.
  int find(std::initializer_list<const char*> names) const;
};

/// Parses the header at the start of `bytes` (the whole file). Keys may come in
/// any order and in any case, '#' lines are comments, unknown keys are ignored.
/// Throws FileError(path) when a key is malformed, sizes disagree, a type/size
/// pair is not a number type, or POINTS != WIDTH * HEIGHT.
Header parse_header(const std::string& bytes, const std::string& path);

}  // namespace l2s::io::pcd
