#pragma once
// Numbers in a packed point record as sensor_msgs/PointField and PCL's
// PCLPointField code their types (1 int8, 2 uint8, 3 int16, 4 uint16, 5 int32,
// 6 uint32, 7 float32, 8 float64; PCL 1.12 adds 9 int64 and 10 uint64), read
// in either byte order. Shared by the PointCloud2 decoder and the PCL adapter.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace l2s::detail {

/// Bytes of one element of `type`; 0 for an unknown type.
inline std::size_t point_field_size(std::uint8_t type) {
  switch (type) {
    case 1:
    case 2: return 1;
    case 3:
    case 4: return 2;
    case 5:
    case 6:
    case 7: return 4;
    case 8:
    case 9:
    case 10: return 8;
    default: return 0;
  }
}

template <typename T>
double load_point_value(const std::uint8_t* p, bool swap) {
  std::uint8_t raw[sizeof(T)];
  std::memcpy(raw, p, sizeof(T));
  if (swap) std::reverse(raw, raw + sizeof(T));
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return static_cast<double>(value);
}

/// The element of `type` at `p` as a double; `swap`: its bytes are in the
/// other order than the host's. The caller has checked the type's size.
inline double load_point_field(const std::uint8_t* p, std::uint8_t type, bool swap) {
  switch (type) {
    case 1: return load_point_value<std::int8_t>(p, swap);
    case 2: return load_point_value<std::uint8_t>(p, swap);
    case 3: return load_point_value<std::int16_t>(p, swap);
    case 4: return load_point_value<std::uint16_t>(p, swap);
    case 5: return load_point_value<std::int32_t>(p, swap);
    case 6: return load_point_value<std::uint32_t>(p, swap);
    case 7: return load_point_value<float>(p, swap);
    case 9: return load_point_value<std::int64_t>(p, swap);
    case 10: return load_point_value<std::uint64_t>(p, swap);
    default: return load_point_value<double>(p, swap);
  }
}

}  // namespace l2s::detail
