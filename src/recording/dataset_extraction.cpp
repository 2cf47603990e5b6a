// A recording to a dataset folder in two passes over the chosen topics: the
// first reads each message's header stamp and pairs the sweeps with the
// images (or a second lidar's sweeps); the second decodes the paired messages and writes each frame once
// its sweep and images are in. The folder is written under a temporary name
// beside its place and renamed when complete.
#include <l2s/recording/dataset_extraction.hpp>

#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/recording/point_cloud2.hpp>
#include <l2s/recording/ros_messages.hpp>

#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <unistd.h>

namespace l2s {
namespace {

namespace fs = std::filesystem;

/// Where each paired message goes: (topic, index in its topic) -> frame.
struct Slot {
  std::size_t frame;
  int part;  ///< 0 lidar, 1 left, 2 right
};

struct PendingFrame {
  io::Frame frame;
  int parts = 0;
};

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

/// A folder beside `folder`, removed unless released.
class TemporaryFolder {
 public:
  explicit TemporaryFolder(const fs::path& folder)
      : path_(folder.string() + ".partial-" + std::to_string(::getpid())) {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    if (!released_) fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }
  void release() { released_ = true; }

 private:
  fs::path path_;
  bool released_ = false;
};

}  // namespace

ExtractionReport extract_dataset(const Ros1Bag& bag, const std::string& folder, const ExtractionOptions& options) {
  const fs::path target_folder(folder);
  std::error_code error;
  if (fs::exists(target_folder, error) && !(fs::is_directory(target_folder) && fs::is_empty(target_folder)))
    throw FileError(folder, "exists and is not an empty folder: the dataset is written into a new one");
  ExtractionReport report;
  report.topics = choose_topics(bag, options.topics);
  const RecordingTopics& t = report.topics;
  // A lidar-lidar recording pairs the second lidar's sweeps where the images would be.
  const bool lidar_pair = !t.lidar2.empty();
  const std::string& left_topic = lidar_pair ? t.lidar2 : t.left;

  // Pass 1: every message's header stamp, per topic, in reading order.
  std::map<std::string, std::vector<std::int64_t>> stamps;
  bag.read({t.lidar, left_topic, t.right}, [&](const RecordedMessage& message) {
    try {
      stamps[message.topic].push_back(header_stamp_ns(message.data));
    } catch (const InputError& e) {
      throw FileError(bag.path(), "topic " + message.topic + ": " + e.what());
    }
    return true;
  });
  report.sweeps = stamps[t.lidar].size();
  PairingParams pairing = options.pairing;
  if (lidar_pair) pairing.left_name = "lidar2 sweep";
  const FramePairing paired = pair_in_time(stamps[t.lidar], stamps[left_topic],
                                           t.right.empty() ? std::vector<std::int64_t>{} : stamps[t.right], pairing);
  report.tolerance_s = paired.tolerance_s;
  report.dropped = paired.dropped;
  if (paired.frames.empty())
    throw FileError(bag.path(), "no sweep of " + t.lidar + " pairs with " + (lidar_pair ? "a sweep" : "an image") +
                                    " of " + left_topic +
                                    (paired.dropped.empty() ? "" : " (" + paired.dropped.front() + ")"));

  std::map<std::pair<int, std::size_t>, Slot> slots;
  for (std::size_t f = 0; f < paired.frames.size(); ++f) {
    slots[{0, paired.frames[f].lidar}] = {f, 0};
    slots[{1, paired.frames[f].left}] = {f, 1};
    if (!t.right.empty()) slots[{2, paired.frames[f].right}] = {f, 2};
  }
  const int parts = t.right.empty() ? 2 : 3;

  TemporaryFolder partial(target_folder);
  std::optional<io::DatasetWriter> writer;
  if (lidar_pair) {
    writer.emplace(io::DatasetWriter::lidar_pair(partial.path().string(), options.target));
  } else {
    StereoCamera cameras;
    cameras.left = first_camera_info(bag, t.left_info);
    if (!t.right.empty()) cameras.right = first_camera_info(bag, t.right_info);
    report.raw_images = t.left.find("rect") == std::string::npos;
    cameras.images = report.raw_images ? ImageKind::Raw : ImageKind::Rectified;
    try {
      writer.emplace(partial.path().string(), cameras, options.target,
                     t.right.empty() ? io::CameraLayout::Mono : io::CameraLayout::Stereo);
    } catch (const FileError& e) {
      throw FileError(bag.path(), "camera_info of " + t.left_info + (t.right.empty() ? "" : " and " + t.right_info) +
                                      ": " + e.what());
    }
  }

  // Pass 2: the paired messages decoded, each frame written when complete.
  std::map<std::string, std::size_t> seen;
  std::map<std::size_t, PendingFrame> pending;
  bag.read({t.lidar, left_topic, t.right}, [&](const RecordedMessage& message) {
    const std::size_t index = seen[message.topic]++;
    const int part = message.topic == t.lidar ? 0 : message.topic == left_topic ? 1 : 2;
    const auto slot = slots.find({part, index});
    if (slot == slots.end()) return true;
    PendingFrame& p = pending[slot->second.frame];
    try {
      if (part == 0) p.frame.lidar = decode_point_cloud2(message.data).cloud;
      else if (lidar_pair) p.frame.lidar2 = decode_point_cloud2(message.data).cloud;
      else if (part == 1) p.frame.left = decode_any_image(message);
      else p.frame.right = decode_any_image(message);
    } catch (const InputError& e) {
      throw FileError(bag.path(), "topic " + message.topic + ": " + e.what());
    }
    if (++p.parts < parts) return true;
    char stem[16];
    std::snprintf(stem, sizeof stem, "%06zu", slot->second.frame);
    p.frame.stem = p.frame.lidar_stem = stem;
    try {
      writer->write(p.frame);
    } catch (const ParamError& e) {
      throw FileError(bag.path(), "frame " + std::string(stem) + " (" + left_topic + "): " + e.what());
    }
    pending.erase(slot->second.frame);
    ++report.frames;
    return true;
  });

  if (fs::exists(target_folder, error)) fs::remove(target_folder, error);  // an empty folder, checked above
  fs::rename(partial.path(), target_folder, error);
  if (error) throw FileError(folder, "cannot be made from " + partial.path().string() + ": " + error.message());
  partial.release();
  return report;
}

}  // namespace l2s
