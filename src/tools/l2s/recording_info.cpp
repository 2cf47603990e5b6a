// l2s info RECORDING: what a ROS 1 bag holds, from its index, the layout of
// each point cloud topic from its first message, and the topics a
// calibration would read.

#include "commands.hpp"

#include <l2s/error.hpp>
#include <l2s/recording/frame_pairing.hpp>
#include <l2s/recording/point_cloud2.hpp>
#include <l2s/recording/ros1_bag.hpp>

#include <cstdio>
#include <string>

namespace l2s::cli {
namespace {

const char* type_name(std::uint8_t datatype) {
  static const char* const names[] = {"?", "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  return datatype <= 8 ? names[datatype] : "?";
}

/// "x float32, y float32, ... (1 x 28800 points, little-endian)" of the topic's first message.
std::string cloud_layout(const Ros1Bag& bag, const std::string& topic) {
  std::string out;
  bag.read({topic}, [&](const RecordedMessage& message) {
    const PointCloud2Sweep sweep = decode_point_cloud2(message.data);
    for (const PointCloud2Field& f : sweep.fields) {
      out += (out.empty() ? "" : ", ") + f.name + " " + type_name(f.datatype);
      if (f.count != 1) out += "[" + std::to_string(f.count) + "]";
    }
    out += " (" + std::to_string(sweep.height) + " x " + std::to_string(sweep.width) + " points, " +
           (sweep.big_endian ? "big" : "little") + "-endian, frame " + sweep.frame_id + ")";
    return false;
  });
  return out;
}

/// The topics a calibration would read, or why it cannot choose them.
void print_choice(const Ros1Bag& bag) {
  try {
    const RecordingTopics t = choose_topics(bag);
    std::printf("picks     lidar %s, left %s (%s)", t.lidar.c_str(), t.left.c_str(), t.left_info.c_str());
    if (!t.right.empty()) std::printf(", right %s (%s)", t.right.c_str(), t.right_info.c_str());
    std::printf("\n");
  } catch (const FileError& e) {
    // The bag's path starts the message; the line above names it already.
    std::printf("picks     nothing: %s\n", std::string(e.what()).substr(bag.path().size() + 2).c_str());
  }
}

}  // namespace

bool is_ros1_bag(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return false;
  char start[9] = {};
  const std::size_t read = std::fread(start, 1, 9, file);
  std::fclose(file);
  return read == 9 && std::string(start, 9) == "#ROSBAG V";
}

int print_recording_info(const std::string& path) {
  const Ros1Bag bag(path);
  std::int64_t first = 0, last = 0;
  std::size_t messages = 0;
  for (const RecordedTopic& t : bag.topics()) {
    if (t.messages == 0) continue;
    first = messages == 0 ? t.first_ns : std::min(first, t.first_ns);
    last = messages == 0 ? t.last_ns : std::max(last, t.last_ns);
    messages += t.messages;
  }
  std::printf("recording %s\n", path.c_str());
  std::printf("format    ROS 1 bag (2.0): %zu topic(s), %zu message(s) over %.3f s, from %.3f s (epoch)\n",
              bag.topics().size(), messages, (last - first) * 1e-9, first * 1e-9);
  for (const RecordedTopic& t : bag.topics()) {
    std::printf("  %-32s %-28s %6zu messages", t.topic.c_str(), t.type.c_str(), t.messages);
    if (t.messages > 1 && t.last_ns > t.first_ns)
      std::printf(", %.2f Hz", static_cast<double>(t.messages - 1) / ((t.last_ns - t.first_ns) * 1e-9));
    std::printf("\n");
    if (t.type == "sensor_msgs/PointCloud2" && t.messages > 0)
      std::printf("    fields: %s\n", cloud_layout(bag, t.topic).c_str());
  }
  print_choice(bag);
  return 0;
}

}  // namespace l2s::cli
