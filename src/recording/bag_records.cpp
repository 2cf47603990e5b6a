#include "recording/bag_records.hpp"

#include "recording/byte_reader.hpp"

#include <cstring>

namespace l2s::detail {

BagFields::BagFields(const std::uint8_t* data, std::size_t size) {
  ByteReader reader(data, size);
  while (reader.remaining() > 0) {
    const auto length = reader.read<std::uint32_t>();
    const auto* field = reinterpret_cast<const char*>(reader.take(length, "a header field"));
    const void* equals = std::memchr(field, '=', length);
    if (!equals) throw std::runtime_error("a header field without '=' at byte " + std::to_string(reader.position()));
    const auto name_length = static_cast<std::size_t>(static_cast<const char*>(equals) - field);
    fields_[std::string(field, name_length)] = std::string(field + name_length + 1, length - name_length - 1);
  }
}

const std::string& BagFields::raw(const std::string& name, std::size_t size) const {
  const auto found = fields_.find(name);
  if (found == fields_.end()) throw std::runtime_error("a record without its '" + name + "' field");
  if (size != 0 && found->second.size() != size)
    throw std::runtime_error("field '" + name + "' has " + std::to_string(found->second.size()) + " bytes, not " +
                             std::to_string(size));
  return found->second;
}

std::uint8_t BagFields::u8(const std::string& name) const {
  return static_cast<std::uint8_t>(raw(name, 1)[0]);
}

std::uint32_t BagFields::u32(const std::string& name) const {
  std::uint32_t value;
  std::memcpy(&value, raw(name, 4).data(), 4);
  return value;
}

std::uint64_t BagFields::u64(const std::string& name) const {
  std::uint64_t value;
  std::memcpy(&value, raw(name, 8).data(), 8);
  return value;
}

std::int64_t BagFields::time_ns(const std::string& name) const {
  std::uint32_t parts[2];
  std::memcpy(parts, raw(name, 8).data(), 8);
  return static_cast<std::int64_t>(parts[0]) * 1000000000 + parts[1];
}

std::string BagFields::text(const std::string& name) const { return raw(name, 0); }

std::vector<BagRecord> records_in(const std::vector<std::uint8_t>& buffer) {
  std::vector<BagRecord> records;
  ByteReader reader(buffer.data(), buffer.size());
  while (reader.remaining() > 0) {
    const auto header_size = reader.read<std::uint32_t>();
    const auto* header = reader.take(header_size, "a record header");
    BagFields fields(header, header_size);
    const auto data_size = reader.read<std::uint32_t>();
    const auto* data = reader.take(data_size, "a record's data");
    records.push_back({std::move(fields), data, data_size});
  }
  return records;
}

}  // namespace l2s::detail
