#pragma once
// A dataset folder laid out as DATASET.md says: cameras, target, and frames
// (lidar/*.pcd, left/*.png, right/*.png) matched by file stem.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace l2s::io {

/// One synchronised frame of both sensors.
struct Frame {
  std::string stem;  ///< file stem shared by the three files, e.g. "000000"
  LidarCloud lidar;  ///< ring always filled (recovered when the file had none)
  Image left;        ///< as stored (gray or BGR)
  Image right;
  bool rings_recovered = false;  ///< true when `ring` came from elevations
};

/// Read access to a dataset folder. Opening reads the YAML files and lists the
/// frames; frames are loaded one at a time so that long recordings stream.
class L2S_EXPORT Dataset {
 public:
  /// Throws FileError naming the file and the problem: missing folder or
  /// camera YAML, malformed YAML, a pair that is not rectified, a missing
  /// lidar/, left/ or right/ folder, no frames, or stems that differ between
  /// them (the message lists the first few and which files they lack).
  /// target.yaml is optional (defaults). Stems are sorted; files whose names
  /// start with '.' or have another extension are not frames.
  static Dataset open(const std::string& folder);

  const std::string& folder() const { return folder_; }
  const StereoCamera& cameras() const { return cameras_; }
  const Target& target() const { return target_; }
  bool has_target_file() const { return has_target_file_; }
  const std::vector<std::string>& stems() const { return stems_; }
  std::size_t size() const { return stems_.size(); }

  /// Loads frame `index`; throws FileError when a file is unreadable or an
  /// image size differs from its camera YAML (ParamError when index >= size()).
  /// A sweep without `ring` gets recover_rings() with default parameters.
  Frame load(std::size_t index) const;

  /// ground_truth.yaml when present (synthetic data); FileError when malformed.
  std::optional<Eigen::Isometry3d> ground_truth() const;

  std::string lidar_path(const std::string& stem) const;
  std::string left_path(const std::string& stem) const;
  std::string right_path(const std::string& stem) const;

 private:
  std::string folder_;
  StereoCamera cameras_;
  Target target_;
  bool has_target_file_ = false;
  std::vector<std::string> stems_;
};

/// Writes a dataset folder: creates it and its sub-folders, writes the camera
/// and target YAMLs at construction, then frames one at a time. Every file is
/// written atomically, and the result passes Dataset::open and check_dataset.py.
class L2S_EXPORT DatasetWriter {
 public:
  /// Throws FileError when the pair is not rectified (as read_stereo_camera
  /// checks) or a folder cannot be created, ParamError for an impossible target.
  DatasetWriter(const std::string& folder, const StereoCamera& cameras, const Target& target);

  /// Writes lidar/STEM.pcd, left/STEM.png, right/STEM.png (an existing frame of
  /// that stem is replaced). Throws ParamError when the stem is not a plain file
  /// name or an image size differs from its camera.
  void write(const Frame& frame, PcdEncoding encoding = PcdEncoding::Binary) const;
  /// Writes ground_truth.yaml (key T_lidar_camera).
  void write_ground_truth(const Eigen::Isometry3d& T_lidar_camera) const;

  const std::string& folder() const { return folder_; }

 private:
  std::string folder_;
  StereoCamera cameras_;
};

}  // namespace l2s::io
