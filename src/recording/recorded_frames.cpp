// A recording's frames in two kinds of pass over its chosen topics: the
// first (at construction) reads each message's header stamp and pairs the
// sweeps with the images (or a second lidar's sweeps); each later one
// decodes the paired messages and hands out each frame once its sweep and
// images are in, in frame order.
#include <l2s/recording/recorded_frames.hpp>

#include <l2s/error.hpp>
#include <l2s/recording/point_cloud2.hpp>
#include <l2s/recording/ros_messages.hpp>

#include <cstdio>
#include <map>
#include <optional>
#include <utility>

namespace l2s {
namespace {

enum Part { Lidar = 0, Left = 1, Right = 2 };

CameraInfo first_camera_info(const Ros1Bag& bag, const std::string& topic) {
  std::optional<CameraInfo> camera;
  bag.read({topic}, [&](const RecordedMessage& message) {
    try {
      camera = decode_camera_info(message.data).camera;
    } catch (const InputError& e) {
      throw FileError(bag.path(), "topic " + topic + ": " + e.what());
    }
    return false;
  });
  if (!camera) throw FileError(bag.path(), "topic " + topic + ": no message");
  return *camera;
}

Image decode_any_image(const RecordedMessage& message) {
  return message.type == "sensor_msgs/CompressedImage" ? decode_compressed_image(message.data).image
                                                       : decode_image(message.data).image;
}

}  // namespace

RecordedFrames::RecordedFrames(const Ros1Bag& bag, const RecordingTopics& topics, const PairingParams& pairing)
    : bag_(&bag), topics_(choose_topics(bag, topics)) {
  const RecordingTopics& t = topics_;
  const std::string& second = lidar_pair() ? t.lidar2 : t.left;
  std::map<std::string, std::vector<std::int64_t>> stamps;
  bag.read({t.lidar, second, t.right}, [&](const RecordedMessage& message) {
    try {
      stamps[message.topic].push_back(header_stamp_ns(message.data));
    } catch (const InputError& e) {
      throw FileError(bag.path(), "topic " + message.topic + ": " + e.what());
    }
    return true;
  });
  sweeps_ = stamps[t.lidar].size();
  PairingParams params = pairing;
  if (lidar_pair()) params.left_name = "lidar2 sweep";
  pairing_ = pair_in_time(stamps[t.lidar], stamps[second],
                          t.right.empty() ? std::vector<std::int64_t>{} : stamps[t.right], params);
  if (pairing_.frames.empty())
    throw FileError(bag.path(), "no sweep of " + t.lidar + " pairs with " + (lidar_pair() ? "a sweep" : "an image") +
                                    " of " + second +
                                    (pairing_.dropped.empty() ? "" : " (" + pairing_.dropped.front() + ")"));
  if (lidar_pair()) return;
  cameras_.left = first_camera_info(bag, t.left_info);
  if (!t.right.empty()) cameras_.right = first_camera_info(bag, t.right_info);
  cameras_.images = t.left.find("rect") == std::string::npos ? ImageKind::Raw : ImageKind::Rectified;
}

std::string RecordedFrames::stem(std::size_t index) {
  char stem[24];
  std::snprintf(stem, sizeof stem, "%06zu", index);
  return stem;
}

void RecordedFrames::read(const std::function<bool(RecordedFrame&&)>& visit) const {
  read_frames(0, size(), visit);
}

RecordedFrame RecordedFrames::load(std::size_t index) const {
  if (index >= size())
    throw ParamError("index", std::to_string(index) + " is past the last of " + std::to_string(size()) +
                                  " frames of " + bag_->path());
  RecordedFrame loaded;
  read_frames(index, index + 1, [&loaded](RecordedFrame&& frame) {
    loaded = std::move(frame);
    return false;
  });
  return loaded;
}

void RecordedFrames::read_frames(std::size_t first, std::size_t last,
                                 const std::function<bool(RecordedFrame&&)>& visit) const {
  const RecordingTopics& t = topics_;
  const std::string& second = lidar_pair() ? t.lidar2 : t.left;
  // Where each paired message goes: (part, index in its topic) -> frame.
  std::map<std::pair<int, std::size_t>, std::size_t> frame_of;
  for (std::size_t f = first; f < last; ++f) {
    frame_of[{Lidar, pairing_.frames[f].lidar}] = f;
    frame_of[{Left, pairing_.frames[f].left}] = f;
    if (!t.right.empty()) frame_of[{Right, pairing_.frames[f].right}] = f;
  }
  const int parts = t.right.empty() ? 2 : 3;

  struct Pending {
    RecordedFrame frame;
    int parts = 0;
  };
  std::map<std::size_t, Pending> pending;  // frames begun or complete, not yet visited
  std::size_t next = first;                // the frame to visit next
  std::map<std::string, std::size_t> seen;
  bool stopped = false;
  bag_->read({t.lidar, second, t.right}, [&](const RecordedMessage& message) {
    const std::size_t index = seen[message.topic]++;
    const int part = message.topic == t.lidar ? Lidar : message.topic == second ? Left : Right;
    const auto slot = frame_of.find({part, index});
    if (slot == frame_of.end()) return true;
    Pending& p = pending[slot->second];
    RecordedFrame& recorded = p.frame;
    try {
      if (part == Lidar || lidar_pair()) {
        PointCloud2Sweep sweep = decode_point_cloud2(message.data);
        (part == Lidar ? recorded.frame.lidar : recorded.frame.lidar2) = std::move(sweep.cloud);
        (part == Lidar ? recorded.lidar_rows : recorded.lidar2_rows) = sweep.height;
      } else {
        (part == Left ? recorded.frame.left : recorded.frame.right) = decode_any_image(message);
      }
    } catch (const InputError& e) {
      throw FileError(bag_->path(), "topic " + message.topic + ": " + e.what());
    }
    ++p.parts;
    // Messages of neighbouring frames interleave: a frame is visited once it
    // and every frame before it are complete, so frames come out in order.
    for (auto it = pending.find(next); it != pending.end() && it->second.parts == parts; it = pending.find(next)) {
      RecordedFrame frame = std::move(it->second.frame);
      pending.erase(it);
      frame.index = next;
      frame.frame.stem = frame.frame.lidar_stem = stem(next);
      ++next;
      if (!visit(std::move(frame))) {
        stopped = true;
        return false;
      }
    }
    return next < last;
  });
  if (!stopped && next < last)
    throw FileError(bag_->path(), "frame " + stem(next) + ": its messages are no longer where the first pass found them");
}

}  // namespace l2s
