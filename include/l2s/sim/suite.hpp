#pragma once
// The paper's experiments (Sec. IV-B, Figs. 5-7) as a plan of calibration runs
// on simulated data: which cells exist, their seeds, and how one group of cells
// that share simulated frames is run (simulate -> calibrate -> evaluate, in
// memory). `l2s suite` schedules the groups; suite_results.hpp records them.

#include <l2s/export.hpp>
#include <l2s/sim/board_draw.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace l2s::sim {

/// What to run. Experiments: "frames" (Fig. 5), "noise" (Fig. 6), "lidars"
/// (Fig. 7), "quick" (a CI smoke test: 3 settings, VLP-16, K = 1, 10 frames),
/// "scenes" (`scene_count` randomised scenes, sim::make_random_scene: other
/// rigs, lenses, raw images, boards, backgrounds, light, lidars and their
/// quirks; one run per scene, `setting` numbers the scene), or a pose
/// experiment (is_pose_experiment).
struct L2S_SUITE_EXPORT SuiteOptions {
  std::vector<std::string> experiments = {"frames", "noise", "lidars"};
  /// Calibrator presets; "mono" (scenes only) is the default preset on the
  /// rig's left camera alone, which finds the board by its markers: what a
  /// stereo result is weighed against, scene by scene.
  std::vector<std::string> presets = {"default", "paper"};
  int repeats = 3;         ///< repetitions per cell (independent seeds), >= 1
  std::uint64_t seed = 1;  ///< base seed; every cell's seed derives from it
  int scene_count = 20;    ///< scenes of the "scenes" experiment, >= 1
  int scene_frames = 20;   ///< frames per scene (2 s at 10 Hz: a ring-free lidar needs them)
  BoardDraw scene_boards = BoardDraw::All;  ///< the boards the "scenes" experiment draws

  /// Throws ParamError naming the field.
  void validate() const;
};

/// The experiments of issue 9 that record five board poses per setting
/// (VLP-16, K = 1, 10 frames a pose, moving frames between) and evaluate each
/// run after 1, 2, 3 and 5 poses (`scene` holds the poses and the uncertainty's
/// coverage): "poses" (the stereo rig), "mono" (its left camera alone, the
/// board carrying ArUco markers) and "lidar-pair" (the VLP-16 and an HDL-32E,
/// T_lidar_lidar2).
inline bool is_pose_experiment(const std::string& experiment) {
  return experiment == "poses" || experiment == "mono" || experiment == "lidar-pair";
}

/// One calibration run: simulated data, preset, and how often it is evaluated.
struct L2S_SUITE_EXPORT SuiteCell {
  std::string experiment;
  int setting = 1;          ///< Table I setting, 1..9 (scenes: the scene's number)
  std::string lidar;        ///< vlp16 | hdl32 | hdl64 (scenes: "random", the scene draws it)
  double noise_k = 1.0;     ///< noise factor K
  int frames = 30;          ///< frames added
  std::string preset;       ///< default | paper | mono (SuiteOptions::presets)
  int repetition = 0;       ///< 0..repeats-1
  std::uint64_t seed = 0;   ///< simulation seed (SimulationConfig::seed)
  bool every_frame = false; ///< evaluated after each added frame (Fig. 5), else once at the end

  /// Rows the cell writes: one per evaluation (pose experiments: after 1, 2, 3 and 5 poses).
  int rows() const { return is_pose_experiment(experiment) ? 4 : every_frame ? frames : 1; }
  /// Identity of the cell within results (seed and frames excluded).
  std::string key() const;
};

/// Cells that share one simulated sequence (same experiment, setting, K,
/// repetition, hence the same seed and images): one per lidar and preset.
struct SuiteGroup {
  std::string experiment;
  int setting = 1;
  double noise_k = 1.0;
  int frames = 30;
  int repetition = 0;
  std::uint64_t seed = 0;
  BoardDraw boards = BoardDraw::All;  ///< scenes: the boards the scene draws
  std::vector<SuiteCell> cells;
};

/// Simulation seed of a group, a pure function of its coordinates; the lidar
/// model is left out on purpose so that all lidars of a group see the same
/// stereo frames (and `l2s simulate --seed` reproduces any row).
L2S_SUITE_EXPORT std::uint64_t suite_seed(std::uint64_t base_seed, const std::string& experiment, int setting,
                         double noise_k, int repetition);

/// The groups of the requested experiments in a fixed order. Throws ParamError.
L2S_SUITE_EXPORT std::vector<SuiteGroup> make_suite_plan(const SuiteOptions& options);

/// One evaluation of one cell: a line of results.csv.
struct L2S_SUITE_EXPORT SuiteRow {
  std::string experiment;
  int setting = 1;
  std::string lidar;
  double noise_k = 1.0;
  int frames = 0;            ///< frames added when evaluated
  std::string preset;
  std::uint64_t seed = 0;
  int repetition = 0;
  bool success = false;
  std::string reason;        ///< why not, when !success
  double e_t = 0.0;          ///< [m] translation error (NaN on failure)
  double e_r = 0.0;          ///< [rad] rotation error (NaN on failure)
  int lidar_frames = 0;      ///< frames whose lidar branch found four centres
  int camera_frames = 0;     ///< frames whose camera branch found four centres
  double wall_s = 0.0;       ///< [s] calibration time of this run so far (simulation excluded)
  std::string scene;         ///< scenes: what was drawn (RandomScene::summary), else empty
  std::string verdict;       ///< the scene check's verdict (ok | suspect | failed), empty when not checked
  int covered = -1;          ///< DoFs (of six) whose true error the result's 95 % bound covers; -1: no valid uncertainty
  std::string check_reasons; ///< the scene check's reasons for its verdict, joined by " | " (empty when ok)
  /// [m] rms distance of the result's lidar (camera) centres from the true hole
  /// centres, in that sensor's frame: which branch an error comes from (NaN on failure)
  double e_lidar_centres = std::nan("");
  double e_camera_centres = std::nan("");
  /// [m], [rad] The result's stated 95 % bounds on its translation and
  /// rotation (translation_bound_95, rotation_bound_95): an error beyond
  /// them is one the result did not admit to (NaN: no valid uncertainty)
  double bound_t = std::nan("");
  double bound_r = std::nan("");
  // --- scenes: what was drawn, in columns of their own (empty / NaN otherwise) ---
  std::string face;           ///< the board's face (name_of(BoardTexture)): matte, wood, speckle, ...
  std::string markers;        ///< the markers' dictionary (DICT_...), empty for a board without
  double roll = std::nan(""); ///< [rad] the rig's roll about its optical axis, (-pi, pi]
  std::string lens;           ///< rectified | raw plumb_bob | raw equidistant

  /// The key of the cell it belongs to (SuiteCell::key).
  std::string cell_key() const;

  /// A cell's row before any evaluation: its identity, no outcome, NaN errors.
  static SuiteRow of(const SuiteCell& cell);
};

/// Simulates a group's frames once and calibrates each of `cells` (a subset of
/// group.cells) on them: one simulator per lidar, one camera branch per preset
/// and frame. Rows come in cell order, each cell's evaluations in frame order.
/// A simulator that cannot place the board makes its cells failed rows (with
/// the reason), never an exception. `threads` goes to the simulator (0 = all
/// cores); `on_frame` is called after each frame.
L2S_SUITE_EXPORT std::vector<SuiteRow> run_suite_group(const SuiteGroup& group, const std::vector<SuiteCell>& cells,
                                      int threads = 0, const std::function<void()>& on_frame = {});

}  // namespace l2s::sim
