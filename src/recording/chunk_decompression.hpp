#pragma once
// The compressions a ROS 1 bag's chunks may use: none, bz2 and lz4 (the
// frame format, as ROS's roslz4 writes it).

#include <cstdint>
#include <string>
#include <vector>

namespace l2s::detail {

/// The chunk's records, `size` bytes once decompressed. Throws
/// std::runtime_error saying what failed: an unknown compression, data that
/// does not decompress, or a size other than `size`.
std::vector<std::uint8_t> decompress_chunk(const std::string& compression, const std::uint8_t* data,
                                           std::size_t data_size, std::size_t size);

}  // namespace l2s::detail
