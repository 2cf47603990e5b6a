#pragma once
// Lidar-lidar recordings (issue 9, "Lidar to lidar"): two lidars of any
// models (spinning or ring-free) look at the board, at one or several board
// poses with moving frames between them. The second lidar stands at a
// realistic pose near the first (drawn from the seed: up to 1 m away, some
// yaw, pitch and roll) from which it sees every board pose. No images are
// made; the board poses are placed as for a lidar-camera rig (the config's
// camera is a virtual one beside the lidars that only steers the placement).

#include <l2s/export.hpp>
#include <l2s/sim/multi_pose.hpp>
#include <l2s/sim/simulation.hpp>

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace l2s::sim {

/// What defines a lidar-lidar dataset. Same config -> same bytes.
struct L2S_SIM_EXPORT LidarPairConfig {
  /// The first lidar (base.lidar at base.setting), board, scene, noise, seed
  /// and lidar quirks (applied to both lidars); base.frames = frames per pose.
  SimulationConfig base;
  std::string lidar2 = "hdl32";  ///< vlp16 | hdl32 | hdl64 | avia | mid360
  /// Pose of lidar2 in the camera body frame; empty: drawn from base.seed
  /// near the first lidar (redrawn until it sees every board pose).
  std::optional<SensorSetting> lidar2_setting;
  int poses = 1;          ///< board poses, 1..5
  int moving_frames = 2;  ///< frames between consecutive poses with the board on its way, 0..10

  /// Throws ParamError naming the field.
  void validate() const;
};

class L2S_SIM_EXPORT LidarPairSimulator {
 public:
  /// Throws ParamError on a bad config; Error when no board pose passes the
  /// placement check for both lidars (lidar2 at its given pose, or at any of
  /// the mounts drawn for it); with a given pose and strict_placement off, a
  /// warning and the first lidar's poses instead. Fewer poses than asked for
  /// give a warning.
  explicit LidarPairSimulator(LidarPairConfig config);
  ~LidarPairSimulator();
  LidarPairSimulator(LidarPairSimulator&&) noexcept;
  LidarPairSimulator& operator=(LidarPairSimulator&&) noexcept;

  int frames() const;                     ///< all frames, static and moving
  /// Frame `index`: lidar and lidar2 filled, images empty. Thread-safe.
  SimulatedFrame frame(int index) const;
  const std::vector<PoseSegment>& segments() const;  ///< in time order
  std::vector<int> moving_frames() const;
  std::vector<BoardPose> poses() const;   ///< the static poses, in order
  const SensorSetting& lidar2_setting() const;   ///< where lidar2 stands (camera body frame)
  Eigen::Isometry3d T_lidar_lidar2() const;      ///< ground truth: p_lidar = T * p_lidar2
  const LidarPairConfig& config() const;
  std::vector<std::string> warnings() const;     ///< e.g. fewer poses found than asked for

  /// Writes the dataset (target.yaml, lidar/, lidar2/, ground_truth.yaml with
  /// T_lidar_lidar2, scene.yaml of the first pose, poses.yaml, lidar2.yaml).
  void write(const std::string& folder, const ProgressCallback& progress = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace l2s::sim
