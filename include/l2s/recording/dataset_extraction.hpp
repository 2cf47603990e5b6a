#pragma once
// A recording turned into a dataset folder (../shared/DATASET.md): the
// chosen topics decoded, the sweeps paired with the images (or a second
// lidar's sweeps) by their header stamps, and the frames written with io::DatasetWriter.

#include <l2s/export.hpp>
#include <l2s/recording/frame_pairing.hpp>
#include <l2s/recording/ros1_bag.hpp>
#include <l2s/target.hpp>

#include <string>
#include <vector>

namespace l2s {

struct ExtractionOptions {
  RecordingTopics topics;  ///< topics named by the user; the rest chosen (choose_topics)
  PairingParams pairing;
  Target target;           ///< written as target.yaml
};

struct ExtractionReport {
  RecordingTopics topics;            ///< the topics read
  bool raw_images = false;           ///< images: raw (an image topic not named *rect*)
  std::size_t sweeps = 0;            ///< lidar messages in the recording
  std::size_t frames = 0;            ///< frames written
  double tolerance_s = 0.0;          ///< the sweep-image tolerance used
  std::vector<std::string> dropped;  ///< as FramePairing::dropped
};

/// Writes `folder` from `bag`. Images count as raw unless their topic's name
/// says "rect" (ROS's image_raw versus image_rect); each camera's model is
/// its first camera_info message. The folder is written beside its final
/// place and renamed into it when complete: a failure leaves nothing there.
/// Throws FileError naming the recording (and the topic) for a fault of the
/// recording (a topic missing or of the wrong type, images without
/// camera_info, an image of another size than its camera_info, no frame
/// paired), or naming `folder` when it exists and is not empty or cannot be
/// written. With `topics.lidar2` named, a lidar-lidar dataset: each sweep
/// of the first lidar paired with the second's nearest one, no cameras.
L2S_EXPORT ExtractionReport extract_dataset(const Ros1Bag& bag, const std::string& folder,
                                            const ExtractionOptions& options = {});

}  // namespace l2s
