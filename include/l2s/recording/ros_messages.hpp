#pragma once
// The camera messages of a ROS 1 recording decoded into the library's types:
// sensor_msgs/Image, sensor_msgs/CompressedImage and sensor_msgs/CameraInfo
// (ROS 1 serialisation, as Ros1Bag hands them over).

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// The header stamp [ns since the epoch] of a message that starts with a
/// std_msgs/Header (PointCloud2, Image, CompressedImage, CameraInfo, ...).
/// Throws InputError("message header", "cut short ...").
L2S_EXPORT std::int64_t header_stamp_ns(const std::vector<std::uint8_t>& message);

/// An image message decoded into an 8-bit gray or BGR Image.
struct RecordedImage {
  std::int64_t stamp_ns = 0;  ///< [ns since the epoch] the header's stamp
  std::string frame_id;
  std::string encoding;       ///< as the message states it (Image) or its format (CompressedImage)
  Image image;                ///< 1 channel (mono, 16-bit ones scaled by 1/256 as cv_bridge does) or 3 (BGR)
};

/// sensor_msgs/Image: mono8, mono16, bgr8, rgb8, bgra8, rgba8, 8UC1, 8UC3,
/// and the 8-bit Bayer mosaics (bayer_rggb8, bayer_bggr8, bayer_gbrg8,
/// bayer_grbg8: demosaiced to BGR). Throws InputError("Image message",
/// fault): cut short, an unknown encoding, a step or data too small for its
/// size.
L2S_EXPORT RecordedImage decode_image(const std::vector<std::uint8_t>& message);

/// sensor_msgs/CompressedImage (jpeg or png; 16-bit and alpha dropped as
/// decode_image does). Throws InputError("CompressedImage message", fault).
L2S_EXPORT RecordedImage decode_compressed_image(const std::vector<std::uint8_t>& message);

/// A camera_info message: the camera model and where it was stamped.
struct RecordedCameraInfo {
  std::int64_t stamp_ns = 0;
  std::string frame_id;
  CameraInfo camera;  ///< K, D, R, P as published; camera_name is the frame id
};

/// sensor_msgs/CameraInfo. Throws InputError("CameraInfo message", fault):
/// cut short, or a size or focal length that is not positive.
L2S_EXPORT RecordedCameraInfo decode_camera_info(const std::vector<std::uint8_t>& message);

}  // namespace l2s
