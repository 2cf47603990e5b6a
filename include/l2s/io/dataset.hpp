#pragma once
// A dataset folder laid out as DATASET.md says: cameras, target, and frames
// (lidar/*.pcd, left/*.png, right/*.png) matched by file stem.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/io/dataset_yaml.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/io/ring_recovery.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace l2s::io {

/// Which cameras a dataset folder holds (DATASET.md v2): left and right, or
/// the left alone (no right.yaml, no right/: a lidar-mono dataset).
enum class CameraLayout { Stereo, Mono };

/// One synchronised frame of both sensors.
struct Frame {
  std::string stem;  ///< file stem shared by the three files, e.g. "000000"
  /// The lidar file the frame pairs with: its own stem, or (`lidar:
  /// accumulated`) the stem of the pose's cloud; empty when no lidar file
  /// covers the frame (image frames before the first lidar file).
  std::string lidar_stem;
  LidarCloud lidar;  ///< ring filled (recovered when the file had none), except for a ring-free scan: empty
  Image left;        ///< as stored (gray or BGR)
  Image right;       ///< empty for a mono dataset
  RingSource ring_source = RingSource::Field;  ///< where `lidar.ring` came from
  /// How the rings were found when the file had none (ring_source != Field):
  /// structure (rings or ring-free), doubts. Empty for RingSource::Field.
  std::optional<RingRecoveryReport> ring_recovery;

  bool rings_recovered() const { return ring_source != RingSource::Field; }

  // A lidar-lidar dataset (Dataset::has_lidar2): the second lidar's sweep,
  // its rings recovered as the first's; the images stay empty.
  LidarCloud lidar2;
  RingSource lidar2_ring_source = RingSource::Field;
  std::optional<RingRecoveryReport> lidar2_ring_recovery;
};

/// Read access to a dataset folder. Opening reads the YAML files and lists the
/// frames; frames are loaded one at a time so that long recordings stream.
/// Thread safety: const functions (frame loading included) may run concurrently.
class L2S_EXPORT Dataset {
 public:
  /// Throws FileError naming the file and the problem: missing folder or
  /// camera YAML, malformed YAML, a dataset.yaml with an unknown key or value,
  /// a camera pair that does not fit the image kind (read_stereo_camera), a
  /// missing lidar/, left/ or right/ folder, no frames, or stems that differ
  /// between them (the message lists the first few and which files they lack).
  /// dataset.yaml (images: rectified) and target.yaml are optional (defaults).
  /// With a `lidar2/` folder the dataset is lidar-lidar (DATASET.md): camera
  /// YAMLs and images are neither needed nor read, and stems must match
  /// between lidar/ and lidar2/ (else FileError naming the folder).
  /// A folder with neither right.yaml nor right/ is a mono dataset (layout()
  /// Mono: only left.yaml is read and checked, cameras().right stays empty);
  /// one of the two without the other is a FileError naming the missing one.
  /// Stems are sorted; files whose names start with '.' or have another
  /// extension are not frames.
  /// With `lidar: accumulated` in dataset.yaml (DATASET.md v3) the frames
  /// are the image frames (left and right must list the same stems), and
  /// each lidar file pairs with the frames from its stem up to the next
  /// lidar file's; a lidar file without an image frame of its stem is a
  /// FileError naming it, as is the form on a lidar-lidar dataset.
  static Dataset open(const std::string& folder);

  const std::string& folder() const { return folder_; }
  /// The cameras; cameras().images says whether the images are raw or
  /// rectified. A mono dataset's right camera is default-constructed (unused).
  const StereoCamera& cameras() const { return cameras_; }
  CameraLayout layout() const { return layout_; }
  bool mono() const { return layout_ == CameraLayout::Mono; }
  bool has_dataset_file() const { return has_dataset_file_; }  ///< dataset.yaml present
  /// What a user should know before trusting the folder (e.g. images declared
  /// rectified while a camera has distortion), one line each; the library
  /// does not print them, tools do.
  const std::vector<std::string>& warnings() const { return warnings_; }
  const Target& target() const { return target_; }
  bool has_target_file() const { return has_target_file_; }
  const std::vector<std::string>& stems() const { return stems_; }
  /// A lidar-lidar dataset: frames hold lidar and lidar2, no images, no cameras.
  bool has_lidar2() const { return has_lidar2_; }
  /// `lidar: sweeps` (one sweep per frame) or `lidar: accumulated` (one
  /// cloud per static pose, beside all its image frames).
  LidarForm lidar_form() const { return lidar_form_; }
  bool accumulated() const { return lidar_form_ == LidarForm::Accumulated; }
  /// Frame.lidar_stem of frame `index` (ParamError when index >= size()).
  const std::string& lidar_stem(std::size_t index) const;
  /// The stems of the lidar files, sorted: one per frame, or one per pose.
  const std::vector<std::string>& lidar_stems() const { return lidar_stems_; }
  std::size_t size() const { return stems_.size(); }

  /// Loads frame `index`; throws FileError when a file is unreadable or an
  /// image size differs from its camera YAML (ParamError when index >= size()).
  /// A sweep without `ring` gets its rings from its rows when it is organised
  /// and they are lasers (rings_from_rows), else from the laser model
  /// (recover_ring_structure), both with default parameters.
  Frame load(std::size_t index) const;
  /// load() without the lidar file (Frame.lidar empty, lidar_stem set): the
  /// image frames of an accumulated cloud, whose cloud is read once.
  Frame load_images(std::size_t index) const;

  /// ground_truth.yaml when present (synthetic data); FileError when malformed.
  /// Its key is T_lidar_lidar2 for a lidar-lidar dataset, else T_lidar_camera.
  std::optional<Eigen::Isometry3d> ground_truth() const;

  std::string lidar_path(const std::string& stem) const;
  std::string left_path(const std::string& stem) const;
  std::string right_path(const std::string& stem) const;
  std::string lidar2_path(const std::string& stem) const;

 private:
  std::string folder_;
  StereoCamera cameras_;
  CameraLayout layout_ = CameraLayout::Stereo;
  Target target_;
  bool has_target_file_ = false;
  bool has_dataset_file_ = false;
  bool has_lidar2_ = false;
  LidarForm lidar_form_ = LidarForm::Sweeps;
  std::vector<std::string> warnings_;
  std::vector<std::string> stems_;
  std::vector<std::string> lidar_stems_;
  std::vector<std::string> lidar_of_frame_;  // lidar_stem() of each frame
};

/// Writes a dataset folder: creates it and its sub-folders, writes the camera
/// and target YAMLs at construction, then frames one at a time. Every file is
/// written atomically, and the result passes Dataset::open and check_dataset.py.
/// Thread safety: one thread at a time per writer.
class L2S_EXPORT DatasetWriter {
 public:
  /// Writes dataset.yaml (images: raw) for raw cameras; rectified ones need
  /// none (the default). Throws FileError when the pair does not fit its image
  /// kind (as read_stereo_camera checks) or a folder cannot be created,
  /// ParamError for an impossible target. A Mono layout writes the left
  /// camera alone (cameras.right is ignored; a right.yaml left in the folder
  /// by an earlier dataset is removed).
  DatasetWriter(const std::string& folder, const StereoCamera& cameras, const Target& target,
                CameraLayout layout = CameraLayout::Stereo);

  /// A lidar-lidar dataset: lidar/ and lidar2/ and target.yaml, no cameras.
  /// Its write() takes frame.lidar and frame.lidar2 (images are ignored).
  static DatasetWriter lidar_pair(const std::string& folder, const Target& target);

  /// Writes lidar/STEM.pcd, left/STEM.png, right/STEM.png (no right image for
  /// a Mono layout; lidar2/STEM.pcd alone beside lidar/ for a lidar pair; an
  /// existing frame of that stem is replaced). Throws ParamError when the stem is not a plain file
  /// name or an image size differs from its camera.
  void write(const Frame& frame, PcdEncoding encoding = PcdEncoding::Binary) const;
  /// A `lidar: accumulated` dataset (DATASET.md v3): the images of a frame
  /// alone (left/STEM.png, right/STEM.png), checked as write() checks them.
  void write_images(const Frame& frame) const;
  /// A `lidar: accumulated` dataset: one static pose's accumulated cloud as
  /// lidar/STEM.pcd (STEM: the first image frame of the pose), and
  /// dataset.yaml saying `lidar: accumulated`. Throws ParamError for a stem
  /// that is not a plain file name.
  void write_accumulated_lidar(const std::string& stem, const LidarCloud& cloud,
                               PcdEncoding encoding = PcdEncoding::Binary) const;
  /// Writes ground_truth.yaml (key T_lidar_camera).
  void write_ground_truth(const Eigen::Isometry3d& T_lidar_camera) const;
  /// Writes ground_truth.yaml of a lidar-lidar dataset (key T_lidar_lidar2).
  void write_ground_truth_lidar2(const Eigen::Isometry3d& T_lidar_lidar2) const;

  const std::string& folder() const { return folder_; }

 private:
  DatasetWriter() = default;
  std::string folder_;
  StereoCamera cameras_;
  bool lidar_pair_ = false;  // lidar/ + lidar2/, no images
  CameraLayout layout_ = CameraLayout::Stereo;
};

}  // namespace l2s::io
