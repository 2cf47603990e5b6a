#pragma once
// From a recording's streams to calibration frames: which topics are the
// lidar and the cameras, and which sweep goes with which images, by their
// stamps.

#include <l2s/export.hpp>
#include <l2s/recording/ros1_bag.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// The topics a calibration reads from a recording (empty: none, or not chosen).
struct RecordingTopics {
  std::string lidar;       ///< sensor_msgs/PointCloud2
  std::string lidar2;      ///< a second PointCloud2 topic (lidar-lidar)
  std::string left;        ///< sensor_msgs/Image or CompressedImage
  std::string right;
  std::string left_info;   ///< sensor_msgs/CameraInfo of the left camera
  std::string right_info;
};

/// The topics of `bag` a calibration would read. A topic named in `given`
/// is taken as given (checked to exist and to have the right type);
/// otherwise it is picked when there is one candidate: one point cloud
/// topic (two with `given.lidar2` asked for by name only), image topics
/// told apart by "left" and "right" in their names (one image topic alone
/// is the left camera), and each camera's camera_info in its image topic's
/// namespace. Throws InputError("recording <path>", fault) naming the topic
/// and what is wrong, or the candidates when a choice is ambiguous.
L2S_EXPORT RecordingTopics choose_topics(const Ros1Bag& bag, const RecordingTopics& given = {});

/// Which messages (indices into the stamp lists) form one frame.
struct PairedFrame {
  std::size_t lidar = 0;
  std::size_t left = 0;
  std::size_t right = 0;  ///< unused without a right camera
};

struct FramePairing {
  std::vector<PairedFrame> frames;
  double tolerance_s = 0.0;         ///< the lidar-image tolerance used
  std::vector<std::string> dropped;  ///< one line per sweep left out and per image no sweep took
};

struct PairingParams {
  /// [s] how far a sweep's and its left image's stamps may lie apart; 0:
  /// half the lidar's median period (a sweep then takes at most the image
  /// nearest its stamp).
  double tolerance_s = 0.0;
  /// [s] how far the left and right images' stamps may lie apart: stereo
  /// rigs trigger both cameras together.
  double stereo_tolerance_s = 0.005;
  /// What the second and third streams are, in the drop reports ("left
  /// image", or "lidar2 sweep" when a second lidar pairs with the first).
  std::string left_name = "left image";
  std::string right_name = "right image";
};

/// Pairs each lidar stamp with the nearest left image stamp within the
/// tolerance, and that image with the nearest right one within the stereo
/// tolerance (`right` empty: a mono camera). Each image serves one frame at
/// most: where two sweeps want the same image, the nearer keeps it. Every
/// sweep and image left out is reported with its stamp and why. Stamps are
/// [ns] in any order; frames come out in lidar stamp order.
L2S_EXPORT FramePairing pair_in_time(const std::vector<std::int64_t>& lidar, const std::vector<std::int64_t>& left,
                                     const std::vector<std::int64_t>& right, const PairingParams& params = {});

}  // namespace l2s
