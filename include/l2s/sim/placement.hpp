#pragma once
// Checks that a board placement gives the calibrator what it needs (paper,
// Sec. III): the whole board and its four holes inside both images, the board
// roughly vertical for both sensors, and every hole crossed by at least two
// lidar rings with rays through the hole and board returns on both sides. A
// ring-free (rosette) lidar instead needs enough returns through each hole
// and on the board around its rim within the accumulation time. Also finds
// such a placement by a deterministic grid search.

#include <l2s/export.hpp>
#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/scene.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/stereo_rig.hpp>

#include <array>
#include <string>
#include <vector>

namespace l2s::sim {

/// How one ring crosses one hole, for the worst azimuth offset of the sweep.
struct RingCrossing {
  int hole = 0;             ///< enum Hole
  int ring = 0;
  int rays_through = 0;     ///< rays guaranteed to pass the hole and hit the wall
  bool board_both_sides = false;  ///< board returns guaranteed left and right of the hole
  bool background_is_wall = true; ///< every ray through the hole hits the wall (or another surface well behind)
  bool occluded = false;          ///< something in front of the board cuts the ring near the hole
  bool counts() const { return rays_through >= 2 && board_both_sides && background_is_wall && !occluded; }
};

struct PlacementRequirements {
  double min_image_margin = 5.0;        ///< [px] board outline to the image border
  int min_rings_per_hole = 2;
  double max_normal_elevation = 0.4;    ///< [rad] board normal from horizontal, each sensor
  double max_incidence = 1.2;           ///< [rad] board normal to the line of sight, each sensor
  // Ring-free (rosette) lidars: the calibrator accumulates the frames of a static board.
  double accumulation_time = 2.0;       ///< [s] of frames accumulated, > 0
  int min_returns_through_hole = 30;    ///< returns through each hole onto a surface >= 0.3 m behind it
  int min_returns_around_hole = 60;     ///< board returns within 4 cm outside each hole's rim
  /// Share of the directions around each hole (twelfths) whose stretch of
  /// rim has board returns, in (0, 1]. 2/3 puts each hole's centre at least
  /// half a radius inside the field of view: a hole the field of view cuts
  /// beyond its centre shows no more than a sliver, which no detector can
  /// place, and a user aims the board so that it is in view.
  double min_rim_in_view = 2.0 / 3.0;
};

/// The verdict for one scene, lidar model and setting.
struct L2S_SIM_EXPORT PlacementReport {
  bool ok = false;
  std::vector<std::string> failures;     ///< one readable line per failed condition
  double image_margin = 0.0;             ///< [px] smallest, over both images
  std::array<int, 4> rings_per_hole{};   ///< rings that count, per hole (spinning lidars)
  int min_rays_second_ring = 0;          ///< over holes: rays of the 2nd-best ring
  bool ring_free = false;                ///< the lidar has no rings: the counts below apply
  std::array<int, 4> returns_through_hole{};  ///< ring-free: within accumulation_time
  std::array<int, 4> returns_around_hole{};   ///< ring-free: board returns around the rim
  std::array<double, 4> rim_in_view{};        ///< ring-free: share of the rim's directions with returns
  double normal_elevation_camera = 0.0;  ///< [rad]
  double normal_elevation_lidar = 0.0;   ///< [rad]
  std::vector<RingCrossing> crossings;   ///< every ring that reaches a hole

  /// Several lines: verdict, margins, and the failures.
  std::string summary() const;
};

/// Checks `scene` for one lidar model mounted as `setting` and the camera `rig`.
L2S_SIM_EXPORT PlacementReport check_placement(const Scene& scene, const LidarModel& lidar,
                                const SensorSetting& setting, const StereoRig& rig = {},
                                const PlacementRequirements& requirements = {});

/// A lidar at its own pose in the camera body frame.
struct MountedLidar {
  LidarModel model;
  SensorSetting setting;
};

/// Grid of board poses the search tries (camera body frame).
struct PlacementSearch {
  std::vector<double> distances{2.4, 2.6, 2.8, 3.0, 3.2, 3.4, 3.6, 3.8, 4.0, 4.2, 4.4, 4.6, 4.8, 5.0, 5.25, 5.5};  ///< [m] x
  std::vector<double> lateral{-1.0, -0.8, -0.6, -0.45, -0.3, -0.15, 0.0, 0.15, 0.3, 0.45, 0.6, 0.8, 1.0};  ///< [m] y
  std::vector<double> heights{-0.9, -0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3, 0.45};  ///< [m] z
  std::vector<double> yaws{-0.35, -0.2, 0.2, 0.35};  ///< [rad] never 0: not axis-aligned
  std::vector<double> pitches{-0.06, 0.06};          ///< [rad] small tilt
  double roll = 0.05;                                                ///< [rad] small in-plane turn
  PlacementRequirements requirements;
  int threads = 0;  ///< 0 = hardware concurrency
  /// Further lidars at their own poses that must pass too (a lidar-lidar
  /// rig's second lidar); their reports follow those of `lidars`.
  std::vector<MountedLidar> also;
  /// Best-rated poses checked exactly before the search gives up, 0: all of
  /// the grid (a grid with no passing pose costs a check of every pose).
  int max_checked = 0;
};

struct PlacementResult {
  bool found = false;
  BoardPose pose;
  double score = 0.0;  ///< larger = more margin
  std::vector<PlacementReport> reports;  ///< one per lidar model, for `pose`
};

/// Finds the board pose of the grid that passes check_placement for every
/// model in `lidars` with the most margin (the grid is rated in closed form,
/// then the best-rated poses are checked exactly, in batches, until some pass). Deterministic: ties go to the
/// first pose in grid order. When none passes, found = false and `pose` is
/// the best-scoring candidate.
L2S_SIM_EXPORT PlacementResult find_placement(const Target& target, const SensorSetting& setting,
                               const std::vector<LidarModel>& lidars, const StereoRig& rig = {},
                               const SceneLayout& layout = {}, const PlacementSearch& search = {});

}  // namespace l2s::sim
