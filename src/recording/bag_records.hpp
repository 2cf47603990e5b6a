#pragma once
// The records of a ROS 1 bag (format 2.0): a header of `name=value` fields,
// then data. The op field tells a record's kind.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace l2s::detail {

enum class BagOp : std::uint8_t {
  MessageData = 0x02,
  BagHeader = 0x03,
  IndexData = 0x04,
  Chunk = 0x05,
  ChunkInfo = 0x06,
  Connection = 0x07,
};

/// The `name=value` fields of a record header (or of a connection's header).
class BagFields {
 public:
  /// Parses `size` bytes of length-prefixed fields; throws ShortBuffer or
  /// std::runtime_error for a field without '='.
  BagFields(const std::uint8_t* data, std::size_t size);

  bool has(const std::string& name) const { return fields_.count(name) != 0; }
  BagOp op() const { return static_cast<BagOp>(u8("op")); }
  std::uint8_t u8(const std::string& name) const;
  std::uint32_t u32(const std::string& name) const;
  std::uint64_t u64(const std::string& name) const;
  /// A ROS time field (seconds, then nanoseconds) in nanoseconds.
  std::int64_t time_ns(const std::string& name) const;
  std::string text(const std::string& name) const;

 private:
  const std::string& raw(const std::string& name, std::size_t size) const;
  std::map<std::string, std::string> fields_;
};

/// A record of a bag held in memory: its fields and where its data lies in
/// the same buffer.
struct BagRecord {
  BagFields fields;
  const std::uint8_t* data;
  std::uint32_t data_size;
};

/// The records of an in-memory buffer (a decompressed chunk), in order.
/// Throws ShortBuffer when one is cut short.
std::vector<BagRecord> records_in(const std::vector<std::uint8_t>& buffer);

}  // namespace l2s::detail
