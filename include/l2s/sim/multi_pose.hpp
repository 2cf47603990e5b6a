#pragma once
// Recordings over several board poses (issue 9, "Several poses"): the board
// stands still for a number of frames at each pose, drawn over the field of
// view the lidar and the camera share, and is carried between poses during a
// few "moving" frames (the board interpolated between the two poses), which a
// calibrator must recognise and skip. Built by composition: one
// DatasetSimulator per static pose and per moving frame.

#include <l2s/export.hpp>
#include <l2s/sim/simulation.hpp>

#include <memory>
#include <string>
#include <vector>

namespace l2s::sim {

/// What defines a multi-pose dataset. Same config -> same bytes.
struct L2S_SIM_EXPORT MultiPoseConfig {
  SimulationConfig base;  ///< sensors, board, scene, noise, seed; base.frames = frames per pose; base.board_pose is ignored
  int poses = 3;          ///< board poses, 1..5
  int moving_frames = 2;  ///< frames between consecutive poses with the board on its way, 0..10

  /// Throws ParamError naming the field.
  void validate() const;
};

/// `count` (1..5) board poses that pass the placement check for `config`'s
/// lidar and camera, spread over their shared view: the first near the
/// centre, then left and near, right and far, then between; so the first P
/// of them are spread for every P. Deterministic. A slot of the view with no
/// passing pose is left out (fewer poses come back).
L2S_SIM_EXPORT std::vector<BoardPose> find_pose_spread(const SimulationConfig& config, int count);

/// One stretch of frames of a multi-pose recording.
struct PoseSegment {
  BoardPose pose;        ///< the board during the stretch
  int first_frame = 0;   ///< index of its first frame
  int frames = 0;        ///< frames in it
  int pose_index = -1;   ///< which static pose, or -1 for a moving frame
};

class L2S_SIM_EXPORT MultiPoseSimulator {
 public:
  /// Throws ParamError on a bad config, Error when no board pose passes the
  /// placement check.
  explicit MultiPoseSimulator(MultiPoseConfig config);
  ~MultiPoseSimulator();
  MultiPoseSimulator(MultiPoseSimulator&&) noexcept;
  MultiPoseSimulator& operator=(MultiPoseSimulator&&) noexcept;

  int frames() const;                          ///< all frames, static and moving
  SimulatedFrame frame(int index) const;       ///< thread-safe
  const std::vector<PoseSegment>& segments() const;  ///< in time order
  std::vector<int> moving_frames() const;      ///< indices of the frames with the board on its way
  std::vector<BoardPose> poses() const;        ///< the static poses, in order
  Eigen::Isometry3d T_lidar_camera() const;    ///< ground truth
  StereoCamera cameras() const;
  const MultiPoseConfig& config() const;
  std::vector<std::string> warnings() const;   ///< e.g. fewer poses found than asked for

  /// Writes the dataset (cameras, target, frames, ground_truth.yaml, scene.yaml
  /// of the first pose and poses.yaml: the segments) into `folder`.
  void write(const std::string& folder, const ProgressCallback& progress = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace l2s::sim
