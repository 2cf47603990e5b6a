// Fuzzes what the recording component parses itself. Built twice:
//   ros1_bag      the input is a bag file: opened, every topic listed, every
//                 message read, each payload decoded as its type says;
//   ros_messages  the input's first byte picks a decoder (PointCloud2, Image,
//                 CompressedImage, CameraInfo, header stamp), the rest is the
//                 message.
// Contract checked: l2s::Error (FileError, InputError) for bad input;
// anything else (another exception, a crash, a sanitizer report, a huge
// allocation) is a finding.
#include <l2s/error.hpp>
#include <l2s/recording/point_cloud2.hpp>
#include <l2s/recording/ros1_bag.hpp>
#include <l2s/recording/ros_messages.hpp>

#include "fuzz_input.hpp"

#include <cstdlib>
#include <vector>

namespace {

/// Decodes `message` as `type` says; bad payloads are InputErrors.
void decode(const std::string& type, const std::vector<std::uint8_t>& message) {
  try {
    if (type == "sensor_msgs/PointCloud2") {
      const auto sweep = l2s::decode_point_cloud2(message);
      if (sweep.cloud.ring.size() > sweep.cloud.size() || sweep.cloud.intensity.size() > sweep.cloud.size()) std::abort();
    } else if (type == "sensor_msgs/Image") {
      const auto image = l2s::decode_image(message);
      if (image.image.pixels.size() != static_cast<std::size_t>(image.image.width) * image.image.height * image.image.channels)
        std::abort();
    } else if (type == "sensor_msgs/CompressedImage") {
      l2s::decode_compressed_image(message);
    } else if (type == "sensor_msgs/CameraInfo") {
      l2s::decode_camera_info(message);
    } else {
      l2s::header_stamp_ns(message);
    }
  } catch (const l2s::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
#if defined(L2S_FUZZ_BAG)
  const std::string& path = l2s::fuzz::write_scratch(data, size, ".bag");
  try {
    const l2s::Ros1Bag bag(path);
    std::size_t messages = 0;
    for (const auto& topic : bag.topics()) messages += topic.messages;
    bag.read({}, [&](const l2s::RecordedMessage& message) {
      decode(message.type, message.data);
      return true;
    });
    (void)messages;
  } catch (const l2s::FileError&) {
  }
#else
  if (size == 0) return 0;
  static const char* const kTypes[] = {"sensor_msgs/PointCloud2", "sensor_msgs/Image", "sensor_msgs/CompressedImage",
                                       "sensor_msgs/CameraInfo", "std_msgs/Header"};
  decode(kTypes[data[0] % 5], std::vector<std::uint8_t>(data + 1, data + size));
#endif
  return 0;
}
