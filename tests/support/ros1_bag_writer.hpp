#pragma once
// A small ROS 1 bag writer for tests: the format the reader is checked
// against, written from the description of bag format 2.0 (no ROS needed),
// with each chunk compression a recorder may use. And the messages drivers
// publish: PointCloud2 of any field layout, Image, CompressedImage and
// CameraInfo.

#include <l2s/camera.hpp>
#include <l2s/types.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace l2s::test {

struct BagMessageToWrite {
  std::string topic;
  std::string type;    ///< e.g. "sensor_msgs/PointCloud2"
  std::int64_t time_ns = 0;
  std::vector<std::uint8_t> data;
};

/// Writes `messages` (in the given order) into chunks of at most
/// `messages_per_chunk` messages, compressed with `compression` ("none",
/// "bz2", "lz4", or any other name, written as given with uncompressed
/// data), each chunk followed by its index records, then the connections and
/// chunk infos, and the bag header pointing at them.
void write_ros1_bag(const std::string& path, const std::vector<BagMessageToWrite>& messages,
                    const std::string& compression, int messages_per_chunk = 2);

/// A field of a PointCloud2 layout: name, datatype (sensor_msgs/PointField).
struct CloudField {
  std::string name;
  std::uint8_t datatype;
};

/// A PointCloud2 message of `cloud` with the fields `layout` (x y z, and any
/// of intensity/i, ring/laser_id, time/t/timestamp, and others written as 0),
/// padded to `point_step` bytes (0: packed), `height` rows, and `big_endian`
/// point data; a field named like a time gets `point_times`' value.
std::vector<std::uint8_t> point_cloud2_message(const LidarCloud& cloud, const std::vector<CloudField>& layout,
                                               std::int64_t stamp_ns, const std::string& frame_id,
                                               std::uint32_t height = 1, bool big_endian = false,
                                               std::uint32_t point_step = 0,
                                               const std::vector<double>& point_times = {});

/// A sensor_msgs/Image of `pixels` (rows of `step` bytes, `encoding` as ROS names it).
std::vector<std::uint8_t> image_message(std::int64_t stamp_ns, const std::string& frame_id, int width, int height,
                                        const std::string& encoding, std::uint32_t step,
                                        const std::vector<std::uint8_t>& pixels, bool big_endian = false);

/// A sensor_msgs/CompressedImage of already compressed `bytes` in `format`.
std::vector<std::uint8_t> compressed_image_message(std::int64_t stamp_ns, const std::string& frame_id,
                                                   const std::string& format, const std::vector<std::uint8_t>& bytes);

/// A sensor_msgs/CameraInfo of `camera` (binning 0, an empty region of interest).
std::vector<std::uint8_t> camera_info_message(std::int64_t stamp_ns, const std::string& frame_id,
                                              const CameraInfo& camera);

}  // namespace l2s::test
