#pragma once
// The simulator's facade: from one flat SimulationConfig to a dataset folder
// laid out as DATASET.md says (the paper's Gazebo test suite, Sec. IV-A).

#include <l2s/export.hpp>
#include <l2s/sim/appearance.hpp>
#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/lidar_quirks.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/scene.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/stereo_renderer.hpp>
#include <l2s/sim/stereo_rig.hpp>
#include <l2s/camera.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace l2s::sim {

/// Everything that defines a synthetic dataset. Same config -> same bytes.
struct L2S_SIM_EXPORT SimulationConfig {
  int setting_index = 1;         ///< 1..9 for Table I, 0 for a custom `setting`
  SensorSetting setting = {-0.8, -0.1, 0.4, 0.0, 0.0, 0.0};  ///< lidar pose in camera body
  std::string lidar = "vlp16";   ///< vlp16 | hdl32 | hdl64 | avia | mid360 (LidarModel::by_name)
  int frames = 30;               ///< >= 1
  double noise_factor = 1.0;     ///< K, >= 0: sigma = K * 0.008 m (lidar), K * 0.007 (image)
  std::uint64_t seed = 1;        ///< S
  Target target;                 ///< the board (Target::preset or target.yaml)
  std::optional<BoardPose> board_pose;  ///< auto-placed (find_placement) when empty
  SceneLayout layout;            ///< wall, ground, clutter
  bool strict_placement = true;  ///< throw when the placement check fails, else warn
  int threads = 0;               ///< 0 = hardware concurrency

  // --- Camera side: the stereo rig and how the scene looks to it ---
  StereoRig rig;                 ///< image size, fov, baseline; lenses, mount, raw or rectified images
  Appearance appearance;         ///< materials, light and shadows, camera response, gray or colour
  /// A lidar-mono dataset (DATASET.md v2): the rig's left camera alone, no
  /// right.yaml or right/ (the right image is neither rendered nor written).
  /// The target must carry markers (Target::markers).
  bool mono = false;
  /// How each of the target's markers is glued off its place in `target`
  /// (one per marker, in layout order, or empty: all where target.yaml puts
  /// them): x, y [m] in the board frame and the turn [rad] in the board
  /// plane about its centre. The images show the markers where they are
  /// glued; the dataset's target.yaml keeps the nominal places, as a user's
  /// does.
  std::vector<Eigen::Vector3d> marker_gluing;

  /// A `lidar: accumulated` dataset (DATASET.md v3) when > 0: the lidar's
  /// returns over this many seconds (10 sweeps a second) as one cloud, as
  /// users of solid-state lidars keep a static board, beside the `frames`
  /// image frames; 0: one sweep per frame. 0..60
  double accumulated_seconds = 0.0;
  /// [m] With accumulated_seconds: only the returns within this distance of
  /// the board's rectangle are kept, as users crop such a cloud; 0: all. >= 0
  double accumulated_crop = 0.0;

  /// The ground truth of this config in the dataset's camera frame
  /// (DATASET.md): the setting's for raw images (the physical left camera)
  /// and the ideal rig; for rectified images of a non-ideal rig, relative to
  /// the rectified left frame.
  Eigen::Isometry3d T_lidar_camera() const;

  // The lidar side of real recordings; all off = the paper's ideal lidar.
  LidarQuirks lidar_quirks;      ///< per-laser table, beam footprint, return mode
  /// The grid the auto-placement searches for the configured lidar alone;
  /// empty: the default grid, one pose for all three spinning models.
  std::optional<PlacementSearch> placement_search;

  /// Table I setting `index` (1..9) with the given lidar model; throws ParamError.
  static SimulationConfig paper(int index, const std::string& lidar = "vlp16");

  /// Throws ParamError naming the field.
  void validate() const;
};

/// One frame in memory, as the dataset folder will hold it.
struct SimulatedFrame {
  LidarCloud lidar;  ///< lidar frame, with intensity and ring (no ring for ring-free lidars)
  Image left;        ///< 8-bit gray (BGR for a colour appearance); raw images when rig.images() is Raw
  Image right;       ///< empty for a mono config
  LidarCloud lidar2; ///< lidar-lidar datasets (LidarPairSimulator): the second lidar; images empty then
};

/// Called after each frame is written: (frames done, frames total). Frames are
/// written by several threads; calls are serialised and `done` counts up by one.
using ProgressCallback = std::function<void(int done, int total)>;

/// Builds the scene of a config once (placement, check, clean images) and then
/// produces frames on demand. The expensive render happens in the constructor.
class L2S_SIM_EXPORT DatasetSimulator {
 public:
  /// Throws ParamError on a bad config, Error when strict_placement is set and
  /// the placement check fails (the message says which hole/ring/image failed).
  explicit DatasetSimulator(SimulationConfig config);
  ~DatasetSimulator();
  DatasetSimulator(DatasetSimulator&&) noexcept;
  DatasetSimulator& operator=(DatasetSimulator&&) noexcept;

  SimulatedFrame frame(int index) const;
  /// The lidar sweep of frame(index) alone, without the images' noise (for
  /// callers that take the images from a simulator of another lidar model).
  LidarCloud sweep(int index) const;

  /// The lidar's returns of sweeps 0 .. 10 * accumulated_seconds - 1 as one
  /// cloud (intensity and ring kept when the sweeps have them), cropped to
  /// accumulated_crop around the board when that is set. ParamError when
  /// accumulated_seconds is 0.
  LidarCloud accumulated_cloud() const;

  /// Writes the whole dataset (cameras, target, frames, ground_truth.yaml and
  /// scene.yaml with the setting and board pose) into `folder`; with
  /// accumulated_seconds, the image frames and one accumulated cloud
  /// (lidar/000000.pcd) in a `lidar: accumulated` dataset.
  void write(const std::string& folder, const ProgressCallback& progress = {}) const;

  const SimulationConfig& config() const;
  const Scene& scene() const;
  const BoardPose& board_pose() const;
  const LidarModel& lidar_model() const;
  const PlacementReport& placement() const;   ///< for the configured lidar
  const CleanStereo& clean_images() const;
  StereoCamera cameras() const;               ///< rig.cameras(): ROS camera_info and the image kind
  Eigen::Isometry3d T_lidar_camera() const;   ///< ground truth, config().T_lidar_camera()
  /// The true centres of the board's holes on its front face, in the lidar
  /// frame and in the camera frame of the result (as T_lidar_camera): what
  /// each sensor's branch should find, to tell which one an error comes from.
  struct HoleTruth {
    HoleCenters lidar{};
    HoleCenters camera{};
  };
  HoleTruth true_hole_centers() const;
  std::vector<std::string> warnings() const;  ///< placement failures when not strict

 private:
  SimulatedFrame images(int index) const;  // frame(index) without its sweep
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes the dataset of `config` into `out_dir` (DatasetSimulator::write).
/// Returns the warnings (empty unless strict_placement is off and the check failed).
L2S_SIM_EXPORT std::vector<std::string> simulate_dataset(const SimulationConfig& config,
                                          const std::string& out_dir,
                                          const ProgressCallback& progress = {});

}  // namespace l2s::sim
