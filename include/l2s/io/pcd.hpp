#pragma once
// PCD v0.7 point clouds (ascii, binary and binary_compressed), read into and
// written from a LidarCloud: x y z, and intensity and ring when present.

#include <l2s/types.hpp>

#include <string>

namespace l2s::io {

enum class PcdEncoding { Ascii, Binary, BinaryCompressed };

/// A PCD file's cloud and how it is organised: HEIGHT > 1 means rows of WIDTH
/// points, stored row after row (point i is in row i / width); drivers may
/// give one row per laser (DATASET.md).
struct PcdFile {
  LidarCloud cloud;
  std::size_t width = 0;   ///< points per row
  std::size_t height = 1;  ///< rows (1: unorganised)
};

/// Reads a PCD file. Fields x, y, z are required (any numeric type); intensity
/// (or `i`) and ring (or `laser_id`) are read when present; other fields, and
/// extra elements of COUNT > 1 fields, are skipped. Organized clouds come back
/// row by row; NaN points are kept. Throws FileError naming the file and the
/// problem (bad header, no x/y/z, truncated or corrupt data, POINTS !=
/// WIDTH * HEIGHT); sizes are checked against the file before allocating.
PcdFile read_pcd_file(const std::string& path);

/// read_pcd_file(path).cloud.
LidarCloud read_pcd(const std::string& path);

/// Writes x y z [intensity] [ring] as float32/float32/uint16 atomically, as
/// `height` rows of N / height points (1: one unorganised row); the same cloud
/// always gives the same bytes. Throws ParamError when intensity or ring has a
/// size other than N, or when `height` does not divide N.
void write_pcd(const std::string& path, const LidarCloud& cloud,
               PcdEncoding encoding = PcdEncoding::Binary, std::size_t height = 1);

}  // namespace l2s::io
