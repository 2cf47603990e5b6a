#pragma once
// ROS 1 bags (format 2.0) read without ROS: the topics a recording holds and
// its messages, topic by topic in time order, one chunk in memory at a time.
// Part of the l2scalib::recording component (find_package(l2scalib
// COMPONENTS recording)), so that programs which read no recordings do not
// link the decompressors.

#include <l2s/export.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace l2s {

/// One message as the recorder stored it.
struct RecordedMessage {
  std::string topic;
  std::string type;               ///< ROS message type, e.g. "sensor_msgs/PointCloud2"
  std::int64_t time_ns = 0;       ///< [ns since the epoch] when the recorder received it
  std::vector<std::uint8_t> data;  ///< the message in ROS 1 serialisation
};

/// A topic of a recording, from its index (no message is decompressed).
struct RecordedTopic {
  std::string topic;
  std::string type;                ///< ROS message type
  std::string md5sum;              ///< of the message definition, as ROS states it
  std::string message_definition;  ///< the full text of the definition the recorder saw
  std::size_t messages = 0;
  std::int64_t first_ns = 0;       ///< [ns] time of the first message (0 without messages)
  std::int64_t last_ns = 0;        ///< [ns] of the last one
};

/// A ROS 1 bag file. Chunks may be stored uncompressed, bz2 or lz4. The index
/// at the end of the file (connections and chunk infos) and the index records
/// after each chunk are read when the bag is opened; message data is read
/// chunk by chunk while visiting. Throws FileError naming the file and the
/// fault: not a bag, a version other than 2.0, no index (a recording that was
/// not closed; `rosbag reindex` writes one), truncated records, an unknown
/// compression, a chunk that does not decompress to its stated size.
class L2S_EXPORT Ros1Bag {
 public:
  explicit Ros1Bag(const std::string& path);
  ~Ros1Bag();
  Ros1Bag(Ros1Bag&&) noexcept;
  Ros1Bag& operator=(Ros1Bag&&) noexcept;

  const std::string& path() const;
  /// Every topic, by name; a topic several publishers recorded is one entry.
  const std::vector<RecordedTopic>& topics() const;
  /// The topic named `topic`, or nullptr.
  const RecordedTopic* topic(const std::string& topic) const;

  /// Calls `visit` with each message of `topics` (every topic when empty):
  /// the chunks in the order of their first message, the messages of a
  /// chunk in time order (a recorder writes its chunks one after another, so
  /// this is the recording's order). `visit` returns false to stop early.
  /// Throws FileError as the constructor does for a chunk that cannot be read.
  void read(const std::vector<std::string>& topics,
            const std::function<bool(const RecordedMessage&)>& visit) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace l2s
