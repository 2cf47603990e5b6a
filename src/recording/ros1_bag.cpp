// A ROS 1 bag, format 2.0: "#ROSBAG V2.0\n", a bag header record pointing at
// the index, then chunks (each followed by index records that list, per
// connection, its messages' times), and at the index position the
// connections and one chunk info per chunk. Opening reads the bag header, the
// index and the index records after each chunk; visiting reads one chunk at
// a time.
#include <l2s/recording/ros1_bag.hpp>

#include <l2s/error.hpp>

#include "recording/bag_records.hpp"
#include "recording/byte_reader.hpp"
#include "recording/chunk_decompression.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

namespace l2s {
namespace {

using detail::BagFields;
using detail::BagOp;

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;

struct Connection {
  std::uint32_t id = 0;
  std::string topic, type, md5sum, message_definition;
  std::size_t messages = 0;
  std::int64_t first_ns = 0, last_ns = 0;
};

struct ChunkInfo {
  std::uint64_t position = 0;
  std::int64_t start_ns = 0;
  std::set<std::uint32_t> connections;  ///< those with messages in the chunk
};

/// A record read from the file: its header fields, and where its data lies.
struct FileRecord {
  BagFields fields;
  std::uint64_t data_position;
  std::uint32_t data_size;
  std::uint64_t next;  ///< the position of the record after it
};

}  // namespace

struct Ros1Bag::Impl {
  std::string path;
  mutable std::ifstream file;
  std::uint64_t file_size = 0;
  std::map<std::uint32_t, Connection> connections;
  std::vector<ChunkInfo> chunks;
  std::vector<RecordedTopic> topics;

  [[noreturn]] void fail(const std::string& problem) const { throw FileError(path, problem); }

  std::vector<std::uint8_t> bytes_at(std::uint64_t position, std::uint64_t count, const char* what) const {
    if (position > file_size || count > file_size - position)
      fail(std::string("truncated: ") + what + " at byte " + std::to_string(position) + " needs " +
           std::to_string(count) + " bytes, the file ends at " + std::to_string(file_size));
    std::vector<std::uint8_t> out(count);
    file.clear();
    file.seekg(static_cast<std::streamoff>(position));
    file.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(count));
    if (!file) fail("read error at byte " + std::to_string(position));
    return out;
  }

  std::uint32_t u32_at(std::uint64_t position, const char* what) const {
    const auto bytes = bytes_at(position, 4, what);
    return detail::ByteReader(bytes.data(), 4).read<std::uint32_t>();
  }

  FileRecord record_at(std::uint64_t position) const {
    const std::uint32_t header_size = u32_at(position, "a record's header length");
    const auto header = bytes_at(position + 4, header_size, "a record header");
    const std::uint64_t data_length_at = position + 4 + header_size;
    const std::uint32_t data_size = u32_at(data_length_at, "a record's data length");
    if (data_size > file_size - std::min(file_size, data_length_at + 4))
      fail("truncated: the record at byte " + std::to_string(position) + " holds " + std::to_string(data_size) +
           " bytes of data, the file ends at " + std::to_string(file_size));
    try {
      return {BagFields(header.data(), header.size()), data_length_at + 4, data_size, data_length_at + 4 + data_size};
    } catch (const std::exception& e) {
      fail("the record at byte " + std::to_string(position) + ": " + e.what());
    }
  }

  void open() {
    file.open(path, std::ios::binary);
    if (!file) fail("cannot be opened");
    file.seekg(0, std::ios::end);
    file_size = static_cast<std::uint64_t>(file.tellg());
    if (file_size < kMagicSize) fail("not a ROS bag: " + std::to_string(file_size) + " bytes, shorter than its magic line");
    const auto magic = bytes_at(0, kMagicSize, "the magic line");
    const std::string line(magic.begin(), magic.end());
    if (line.rfind("#ROSBAG V", 0) != 0) fail("not a ROS bag: it does not start with \"#ROSBAG V\"");
    if (line != kMagic) fail("a ROS bag of version " + line.substr(9, 3) + ": only version 2.0 (ROS 1) is read");
    try {
      read_index();
    } catch (const detail::ShortBuffer& e) {
      fail(std::string("truncated index: ") + e.what());
    } catch (const std::runtime_error& e) {
      if (dynamic_cast<const FileError*>(&e)) throw;
      fail(e.what());
    }
    gather_topics();
  }

  void read_index() {
    const FileRecord header = record_at(kMagicSize);
    if (header.fields.op() != BagOp::BagHeader) fail("no bag header record after the magic line");
    const std::uint64_t index_position = header.fields.u64("index_pos");
    if (index_position == 0)
      fail("has no index: the recording was not closed (`rosbag reindex` writes one)");
    if (index_position >= file_size)
      fail("truncated: its index starts at byte " + std::to_string(index_position) + ", the file ends at " +
           std::to_string(file_size));
    for (std::uint64_t at = index_position; at < file_size;) {
      const FileRecord record = record_at(at);
      const auto data = bytes_at(record.data_position, record.data_size, "an index record's data");
      if (record.fields.op() == BagOp::Connection) {
        Connection c;
        c.id = record.fields.u32("conn");
        c.topic = record.fields.text("topic");
        const BagFields described(data.data(), data.size());
        c.type = described.text("type");
        c.md5sum = described.has("md5sum") ? described.text("md5sum") : "";
        c.message_definition = described.has("message_definition") ? described.text("message_definition") : "";
        connections[c.id] = c;
      } else if (record.fields.op() == BagOp::ChunkInfo) {
        ChunkInfo chunk;
        chunk.position = record.fields.u64("chunk_pos");
        chunk.start_ns = record.fields.time_ns("start_time");
        detail::ByteReader reader(data.data(), data.size());
        for (std::uint32_t k = 0, n = record.fields.u32("count"); k < n; ++k) {
          chunk.connections.insert(reader.read<std::uint32_t>());
          reader.read<std::uint32_t>();  // its message count: the index records give them with times
        }
        chunks.push_back(chunk);
      }
      at = record.next;
    }
    std::stable_sort(chunks.begin(), chunks.end(),
                     [](const ChunkInfo& a, const ChunkInfo& b) { return a.start_ns < b.start_ns; });
    for (const ChunkInfo& chunk : chunks) read_chunk_index(chunk);
  }

  /// The index records that follow a chunk: per connection, its messages' times.
  void read_chunk_index(const ChunkInfo& chunk) {
    const FileRecord record = record_at(chunk.position);
    if (record.fields.op() != BagOp::Chunk)
      fail("the chunk info points at byte " + std::to_string(chunk.position) + ", which is not a chunk");
    for (std::uint64_t at = record.next; at < file_size;) {
      const FileRecord index = record_at(at);
      if (index.fields.op() != BagOp::IndexData) break;
      const auto data = bytes_at(index.data_position, index.data_size, "an index record's data");
      const auto found = connections.find(index.fields.u32("conn"));
      if (found == connections.end())
        fail("the index after the chunk at byte " + std::to_string(chunk.position) + " names connection " +
             std::to_string(index.fields.u32("conn")) + ", which the bag does not describe");
      Connection& c = found->second;
      detail::ByteReader reader(data.data(), data.size());
      for (std::uint32_t k = 0, n = index.fields.u32("count"); k < n; ++k) {
        const auto seconds = reader.read<std::uint32_t>();
        const auto nanoseconds = reader.read<std::uint32_t>();
        reader.read<std::uint32_t>();  // the message's offset in the decompressed chunk
        const std::int64_t t = static_cast<std::int64_t>(seconds) * 1000000000 + nanoseconds;
        c.first_ns = c.messages == 0 ? t : std::min(c.first_ns, t);
        c.last_ns = c.messages == 0 ? t : std::max(c.last_ns, t);
        ++c.messages;
      }
      at = index.next;
    }
  }

  void gather_topics() {
    std::map<std::string, RecordedTopic> by_name;
    for (const auto& [id, c] : connections) {
      auto [it, added] = by_name.try_emplace(c.topic);
      RecordedTopic& t = it->second;
      if (added) {
        t.topic = c.topic, t.type = c.type, t.md5sum = c.md5sum, t.message_definition = c.message_definition;
      }
      if (c.messages == 0) continue;
      t.first_ns = t.messages == 0 ? c.first_ns : std::min(t.first_ns, c.first_ns);
      t.last_ns = t.messages == 0 ? c.last_ns : std::max(t.last_ns, c.last_ns);
      t.messages += c.messages;
    }
    for (auto& [name, t] : by_name) topics.push_back(std::move(t));
  }

  std::vector<std::uint8_t> chunk_records(const ChunkInfo& chunk) const {
    const FileRecord record = record_at(chunk.position);
    const auto data = bytes_at(record.data_position, record.data_size, "a chunk's data");
    try {
      return detail::decompress_chunk(record.fields.text("compression"), data.data(), data.size(),
                                      record.fields.u32("size"));
    } catch (const std::exception& e) {
      fail("the chunk at byte " + std::to_string(chunk.position) + ": " + e.what());
    }
  }
};

Ros1Bag::Ros1Bag(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->open();
}

Ros1Bag::~Ros1Bag() = default;
Ros1Bag::Ros1Bag(Ros1Bag&&) noexcept = default;
Ros1Bag& Ros1Bag::operator=(Ros1Bag&&) noexcept = default;

const std::string& Ros1Bag::path() const { return impl_->path; }

const std::vector<RecordedTopic>& Ros1Bag::topics() const { return impl_->topics; }

const RecordedTopic* Ros1Bag::topic(const std::string& name) const {
  for (const RecordedTopic& t : impl_->topics)
    if (t.topic == name) return &t;
  return nullptr;
}

void Ros1Bag::read(const std::vector<std::string>& topics,
                   const std::function<bool(const RecordedMessage&)>& visit) const {
  const Impl& bag = *impl_;
  std::set<std::uint32_t> wanted;
  for (const auto& [id, c] : bag.connections)
    if (topics.empty() || std::find(topics.begin(), topics.end(), c.topic) != topics.end()) wanted.insert(id);
  for (const ChunkInfo& chunk : bag.chunks) {
    if (std::none_of(chunk.connections.begin(), chunk.connections.end(),
                     [&](std::uint32_t id) { return wanted.count(id) != 0; }))
      continue;
    const std::vector<std::uint8_t> buffer = bag.chunk_records(chunk);
    std::vector<detail::BagRecord> records;
    try {
      records = detail::records_in(buffer);
    } catch (const std::exception& e) {
      bag.fail("the chunk at byte " + std::to_string(chunk.position) + ": " + e.what());
    }
    std::vector<std::pair<std::int64_t, const detail::BagRecord*>> messages;
    for (const detail::BagRecord& record : records) {
      try {
        if (record.fields.op() != BagOp::MessageData || wanted.count(record.fields.u32("conn")) == 0) continue;
        messages.emplace_back(record.fields.time_ns("time"), &record);
      } catch (const std::exception& e) {
        bag.fail("a message in the chunk at byte " + std::to_string(chunk.position) + ": " + e.what());
      }
    }
    std::stable_sort(messages.begin(), messages.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [time, record] : messages) {
      const auto found = bag.connections.find(record->fields.u32("conn"));
      if (found == bag.connections.end())
        bag.fail("a message in the chunk at byte " + std::to_string(chunk.position) + " names an unknown connection");
      RecordedMessage message;
      message.topic = found->second.topic;
      message.type = found->second.type;
      message.time_ns = time;
      message.data.assign(record->data, record->data + record->data_size);
      if (!visit(message)) return;
    }
  }
}

}  // namespace l2s
