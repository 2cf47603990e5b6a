#pragma once
// A recording read as calibration frames: its topics chosen, its sweeps
// paired in time with its images (or a second lidar's sweeps), and the
// paired messages decoded frame by frame, in frame order, a few frames in
// memory at a time. `l2s extract` writes these frames as a dataset folder;
// `l2s calibrate RECORDING` hands them to the calibrator without one.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/recording/frame_pairing.hpp>
#include <l2s/recording/ros1_bag.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace l2s {

/// One paired frame as recorded: io::Frame's stem (the frame's index as
/// "%06zu", the stem `l2s extract` writes it under), sweeps and images as
/// their messages hold them (rings as the message gives them, none
/// recovered), and the sweeps' rows (1: unorganised).
struct RecordedFrame {
  io::Frame frame;
  std::size_t index = 0;
  std::size_t lidar_rows = 1;
  std::size_t lidar2_rows = 1;
};

class L2S_EXPORT RecordedFrames {
 public:
  /// Chooses the topics (choose_topics), reads every header stamp of them
  /// and pairs the frames (pair_in_time), and reads each camera's first
  /// camera_info. Images count as raw unless their topic's name says "rect"
  /// (ROS's image_raw versus image_rect). With `topics.lidar2` named, a
  /// lidar-lidar recording: each sweep of the first lidar paired with the
  /// second's nearest one, no cameras. Throws FileError naming the
  /// recording (and the topic) for a topic missing or of the wrong type,
  /// images without camera_info, a header that cannot be read, or no frame
  /// paired. `bag` must outlive this object.
  explicit RecordedFrames(const Ros1Bag& bag, const RecordingTopics& topics = {}, const PairingParams& pairing = {});

  const Ros1Bag& bag() const { return *bag_; }
  const RecordingTopics& topics() const { return topics_; }
  bool lidar_pair() const { return !topics_.lidar2.empty(); }
  bool mono() const { return !lidar_pair() && topics_.right.empty(); }
  /// The cameras from camera_info (no right one for mono; none for a lidar pair).
  const StereoCamera& cameras() const { return cameras_; }
  bool raw_images() const { return cameras_.images == ImageKind::Raw; }

  std::size_t size() const { return pairing_.frames.size(); }
  std::size_t sweeps() const { return sweeps_; }  ///< lidar messages in the recording
  double tolerance_s() const { return pairing_.tolerance_s; }  ///< the sweep-image tolerance used
  const std::vector<std::string>& dropped() const { return pairing_.dropped; }  ///< as FramePairing::dropped

  /// Reads the recording once and calls `visit` with each frame in index
  /// order, decoded once all its messages are in; `visit` returning false
  /// stops the reading. Throws FileError naming the recording and the topic
  /// for a message that cannot be decoded.
  void read(const std::function<bool(RecordedFrame&&)>& visit) const;
  /// Frame `index` alone (reads the recording up to its last message).
  RecordedFrame load(std::size_t index) const;

  /// The stem of frame `index` ("%06zu").
  static std::string stem(std::size_t index);

 private:
  void read_frames(std::size_t first, std::size_t last, const std::function<bool(RecordedFrame&&)>& visit) const;

  const Ros1Bag* bag_;
  RecordingTopics topics_;
  StereoCamera cameras_;
  FramePairing pairing_;
  std::size_t sweeps_ = 0;
};

}  // namespace l2s
