#pragma once
// std_msgs/Header, the start of every stamped message: seq, stamp, frame_id.

#include "recording/byte_reader.hpp"

#include <cstdint>
#include <string>

namespace l2s::detail {

struct RosHeader {
  std::int64_t stamp_ns = 0;
  std::string frame_id;
};

inline RosHeader read_ros_header(ByteReader& reader) {
  RosHeader header;
  reader.read<std::uint32_t>();  // seq
  const auto seconds = reader.read<std::uint32_t>();
  const auto nanoseconds = reader.read<std::uint32_t>();
  header.stamp_ns = static_cast<std::int64_t>(seconds) * 1000000000 + nanoseconds;
  header.frame_id = reader.read_string();
  return header;
}

}  // namespace l2s::detail
