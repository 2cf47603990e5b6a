// Which topics of a recording a calibration reads: as given, or the one
// candidate of each kind; a camera's camera_info sits beside its images.
#include <l2s/recording/frame_pairing.hpp>

#include <l2s/error.hpp>

#include <algorithm>

namespace l2s {
namespace {

const char* const kCloud = "sensor_msgs/PointCloud2";
const char* const kInfo = "sensor_msgs/CameraInfo";

bool is_image(const std::string& type) {
  return type == "sensor_msgs/Image" || type == "sensor_msgs/CompressedImage";
}

std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

/// The namespace a camera publishes in: /stereo/left for /stereo/left/image_raw
/// and for its /compressed transport.
std::string camera_namespace(std::string topic) {
  const std::string compressed = "/compressed";
  if (topic.size() > compressed.size() && topic.compare(topic.size() - compressed.size(), compressed.size(), compressed) == 0)
    topic.resize(topic.size() - compressed.size());
  const auto slash = topic.rfind('/');
  return slash == std::string::npos ? "" : topic.substr(0, slash);
}

class Chooser {
 public:
  explicit Chooser(const Ros1Bag& bag) : bag_(bag) {}

  [[noreturn]] void fail(const std::string& problem) const { throw FileError(bag_.path(), problem); }

  std::vector<std::string> of_kind(bool (*kind)(const std::string&)) const {
    std::vector<std::string> names;
    for (const RecordedTopic& t : bag_.topics())
      if (kind(t.type)) names.push_back(t.topic);
    return names;
  }

  /// `given` checked to exist with a type `kind` accepts.
  void check(const std::string& given, bool (*kind)(const std::string&), const char* wanted, const char* role) const {
    const RecordedTopic* topic = bag_.topic(given);
    if (!topic) fail("topic " + given + " (" + role + "): not in the recording");
    if (!kind(topic->type)) fail("topic " + given + " (" + role + "): " + topic->type + ", not " + wanted);
    if (topic->messages == 0) fail("topic " + given + " (" + role + "): no messages");
  }

  /// The camera_info beside `image` (same namespace), or a failure naming where it was looked for.
  std::string info_beside(const std::string& image) const {
    const std::string space = camera_namespace(image);
    for (const RecordedTopic& t : bag_.topics())
      if (t.type == kInfo && camera_namespace(t.topic) == space) return t.topic;
    fail("topic " + image + ": images without camera_info (no " + kInfo + " topic in " +
         (space.empty() ? "/" : space) + ")");
  }

 private:
  const Ros1Bag& bag_;
};

bool cloud_type(const std::string& type) { return type == kCloud; }
bool info_type(const std::string& type) { return type == kInfo; }

}  // namespace

RecordingTopics choose_topics(const Ros1Bag& bag, const RecordingTopics& given) {
  const Chooser chooser(bag);
  RecordingTopics out = given;
  const auto clouds = chooser.of_kind(cloud_type);
  if (out.lidar.empty()) {
    const auto others = [&] {
      std::vector<std::string> rest;
      for (const auto& c : clouds)
        if (c != out.lidar2) rest.push_back(c);
      return rest;
    }();
    if (others.empty()) chooser.fail(std::string("no ") + kCloud + " topic for the lidar");
    if (others.size() > 1) chooser.fail("several point cloud topics (" + listed(others) + "): name the lidar's (--lidar-topic)");
    out.lidar = others.front();
  }
  chooser.check(out.lidar, cloud_type, kCloud, "lidar");
  if (!out.lidar2.empty()) {
    chooser.check(out.lidar2, cloud_type, kCloud, "lidar2");
    return out;  // a lidar-lidar recording: no cameras
  }

  const auto images = chooser.of_kind(is_image);
  const auto named = [&](const char* side) {
    std::vector<std::string> found;
    for (const auto& image : images)
      if (image.find(side) != std::string::npos) found.push_back(image);
    return found;
  };
  if (out.left.empty()) {
    const auto lefts = named("left");
    if (lefts.size() == 1)
      out.left = lefts.front();
    else if (lefts.empty() && images.size() == 1)
      out.left = images.front();  // one camera: the left one of DATASET.md's mono layout
    else if (images.empty())
      chooser.fail("no sensor_msgs/Image or CompressedImage topic");
    else
      chooser.fail("image topics " + listed(lefts.empty() ? images : lefts) + ": name the left camera's (--left-topic)");
  }
  chooser.check(out.left, is_image, "sensor_msgs/Image or CompressedImage", "left");
  if (out.right.empty()) {
    const auto rights = named("right");
    if (rights.size() == 1) out.right = rights.front();
    if (rights.size() > 1) chooser.fail("image topics " + listed(rights) + ": name the right camera's (--right-topic)");
  }
  if (!out.right.empty()) chooser.check(out.right, is_image, "sensor_msgs/Image or CompressedImage", "right");
  if (out.left_info.empty()) out.left_info = chooser.info_beside(out.left);
  chooser.check(out.left_info, info_type, kInfo, "left camera_info");
  if (!out.right.empty()) {
    if (out.right_info.empty()) out.right_info = chooser.info_beside(out.right);
    chooser.check(out.right_info, info_type, kInfo, "right camera_info");
  }
  return out;
}

}  // namespace l2s
