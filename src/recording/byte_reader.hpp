#pragma once
// Little-endian fields read off a byte buffer with bounds checks: the ROS 1
// serialisation and the bag format's record headers are both little-endian.

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "ROS 1 serialisation is little-endian; these readers assume a little-endian host"
#endif

namespace l2s::detail {

/// Thrown when a read would pass the end of the buffer; callers turn it into
/// an error that names their input.
struct ShortBuffer : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::size_t position() const { return position_; }
  std::size_t remaining() const { return size_ - position_; }

  template <typename T>
  T read() {
    T value;
    std::memcpy(&value, take(sizeof(T), "a number"), sizeof(T));
    return value;
  }
  std::string read_string() {
    const auto length = read<std::uint32_t>();
    const auto* bytes = take(length, "a string");
    return std::string(reinterpret_cast<const char*>(bytes), length);
  }
  /// `count` bytes, returned in place.
  const std::uint8_t* take(std::size_t count, const char* what) {
    if (count > remaining())
      throw ShortBuffer(std::string(what) + " of " + std::to_string(count) + " bytes at byte " +
                        std::to_string(position_) + " runs past the end (" + std::to_string(size_) + " bytes)");
    const std::uint8_t* at = data_ + position_;
    position_ += count;
    return at;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

}  // namespace l2s::detail
