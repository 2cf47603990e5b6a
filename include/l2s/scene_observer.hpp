#pragma once
// What the calibration check (calibration_check.hpp) keeps of one frame, and
// the stage that makes it. The check compares the whole scene as the two
// sensors saw it, never the four hole centres, so it keeps:
//  - of the lidar sweep: its depth discontinuities (the near side of every
//    range jump: silhouettes of the board, its holes, boxes, posts, the top
//    of a wall against the sky), the board returns, the points where the
//    sweep leaves the board, and an evenly thinned copy of the sweep;
//  - of the left image: the distance from each pixel to its nearest edge
//    (Canny), the coarse stereo depth the camera branch matched anyway, and
//    the board pose the camera branch found.
// Discontinuities follow each ring in azimuth (Levinson and Thrun 2013);
// clouds without rings (solid-state, accumulated rosette scans) are binned on
// a spherical grid of the sensor and compared with the four grid neighbours.
// Everything is small enough for a calibrator to keep a dozen frames.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/stereo_matcher.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace l2s {

/// Distance from each pixel of the rectified left image to its nearest edge.
struct L2S_EXPORT EdgeDistanceMap {
  int width = 0;       ///< [px]
  int height = 0;      ///< [px]
  double unit = 0.25;  ///< [px] per step of `distance`
  std::vector<std::uint8_t> distance;  ///< row-major; 255 means 255 * unit px or farther
  std::size_t edge_pixels = 0;         ///< edge pixels found

  bool empty() const { return distance.empty(); }
  /// [px] at the pixel nearest to `uv`; +inf outside the image.
  double at(double u, double v) const;
};

/// Stereo depth of the rectified left image on a coarse grid of cells.
struct L2S_EXPORT DepthMap {
  int width = 0;      ///< [cells]
  int height = 0;     ///< [cells]
  double cell = 4.0;  ///< [px] side of a cell; cell (i, j) covers left pixels [i * cell, (i + 1) * cell) - 0.5
  std::vector<float> depth;  ///< [m] optical z of the stereo point, NaN = no match
  double depth_noise = 0.0;  ///< [1/m] depth sigma of one match at depth z is depth_noise * z^2
  /// Per cell, 1 where the left image has texture along the rows (a
  /// gradient along them above the image noise): SGBM measures a disparity
  /// only there and fills the rest in from the surroundings (a plain wall
  /// takes depths that slope towards the board before it). Empty when not
  /// measured (SceneObserver::mark_texture).
  std::vector<std::uint8_t> textured;

  bool empty() const { return depth.empty(); }
  /// [m] at the cell holding pixel `uv`; NaN outside or unmatched.
  double at(double u, double v) const;
  /// Row-major index of the cell holding pixel `uv`; -1 outside.
  long cell_index(double u, double v) const;
  /// Whether the cell holding pixel `uv` is textured; true when not measured.
  bool textured_at(double u, double v) const;
};

/// The lidar side of one frame (lidar frame).
struct L2S_EXPORT LidarObservation {
  std::vector<Eigen::Vector3d> scene_edges;  ///< [m] depth discontinuities off the board
  std::vector<Eigen::Vector3d> board_edges;  ///< [m] depth discontinuities on the board (outline, hole rims)
  std::vector<Eigen::Vector3d> board;        ///< [m] board returns of the lidar branch (thinned)
  std::vector<Eigen::Vector3d> hole_centers; ///< [m] the lidar branch's hole centres, when it found them (else empty)
  std::vector<Eigen::Vector3d> scene;        ///< [m] the whole sweep, evenly thinned
  bool ring_free = false;                    ///< discontinuities came from the spherical grid
};

/// The camera side of one frame (the dataset's camera frame, DATASET.md).
struct L2S_EXPORT CameraObservation {
  std::optional<Eigen::Isometry3d> T_camera_board;  ///< the camera branch's board pose, when it found the board
  bool board_pose_refined = false;  ///< T_camera_board is the rim refinement's, not the stereo circles'
  /// The board plane fitted to the stereo points (normal towards the camera):
  /// metric through the baseline alone, so a wrong target size, which biases
  /// the pose's depth, does not bias it.
  std::optional<Plane> stereo_plane;
  /// Share of those stereo points whose image texture runs along the rows
  /// (SceneObserver::row_texture_share), 0..1; NaN when not measured.
  double stereo_row_texture = std::numeric_limits<double>::quiet_NaN();
  EdgeDistanceMap edges;  ///< of the rectified left image; empty when not kept
  DepthMap depth;         ///< coarse stereo depth; empty when none
};

/// Everything the check uses of one frame.
struct L2S_EXPORT CheckFrame {
  std::string id;  ///< frame name
  LidarObservation lidar;
  CameraObservation camera;
};

/// Makes the observations of one frame.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT SceneObserver {
 public:
  struct Params {
    double min_jump = 0.3;        ///< [m] a neighbour this much farther (or no return) marks a discontinuity, > 0
    double relative_jump = 0.05;  ///< ... or this share of the near range, where larger, >= 0
    double gap_factor = 1.5;      ///< ring neighbours farther apart than this many azimuth steps have no return between them, > 1
    double min_range = 0.5;       ///< [m] nearer returns are ignored (mounts, the vehicle), >= 0
    double grid_step = 0.0035;    ///< [rad] cell of the spherical grid for clouds without rings, > 0
    double board_band = 0.05;     ///< [m] a discontinuity this close to the lidar board plane, inside its extent, is a board edge, > 0
    int max_edges = 3000;         ///< discontinuities kept per frame, evenly thinned, >= 10
    int max_board_points = 600;   ///< board returns kept, >= 10
    int max_scene_points = 10000; ///< sweep returns kept, evenly thinned, >= 10
    double canny_low = 40.0;      ///< [Sobel magnitude] Canny hysteresis, low threshold, for an image of full contrast, > 0
    double canny_high = 100.0;    ///< [Sobel magnitude] high threshold, >= canny_low
    /// [Sobel magnitude] What a well-exposed image's strongest edges (its
    /// 99.9th percentile gradient) reach. A darker or flatter image has
    /// every edge's step smaller by the same share, so both Canny
    /// thresholds scale down with it (never below the image's noise), > 0.
    double strong_edge = 200.0;
    double depth_cell = 4.0;      ///< [px] side of a depth-map cell, >= 1
    double depth_jump_margin = 16.0;  ///< [px] stereo depth this close to a depth jump is dropped (SGBM fattens near surfaces), >= 0

    void validate() const;  ///< throws ParamError naming the field
  };

  // Two constructors rather than `Params params = {}` (see PlaneSegmenter).
  SceneObserver();
  explicit SceneObserver(Params params);
  const Params& params() const { return params_; }

  /// The lidar side: `sweep` (the whole sweep, NaN allowed; rings when it has
  /// them), `board` the board returns the lidar branch kept (may be empty).
  LidarObservation observe_lidar(const LidarCloud& sweep, const std::vector<Eigen::Vector3d>& board) const;

  /// Edges of the left image as the dataset holds it (raw images are
  /// rectified here first). Throws ParamError when its size differs from the camera.
  EdgeDistanceMap observe_edges(const Image& left, const StereoCamera& cameras) const;

  /// A coarse depth map from a disparity map of the left image (a stereo
  /// pass of the whole frame; `cameras` give fx * B). Empty when `disparity` is.
  DepthMap observe_depth(const DisparityMap& disparity, const StereoCamera& cameras, double depth_noise) const;
  /// Share of the stereo points `board` (their pixels in `rectified_left`)
  /// whose texture runs along the rows: a gradient across the rows above
  /// the noise, and less than half of it along them. SGBM cannot tell where
  /// along its row such a window matches and fills it in from the
  /// surroundings: the stereo plane of a wood-grain face with the grain
  /// along the rows was up to 2 px of disparity off. 0..1, NaN without
  /// points inside the image.
  double row_texture_share(const Image& rectified_left, const StereoCloud& board) const;
  /// Fills `map.textured` from `rectified_left` (the image `map` was
  /// matched on, same size as the camera). Nothing when `map` is empty.
  void mark_texture(const Image& rectified_left, DepthMap& map) const;

 private:
  Params params_;
};

}  // namespace l2s
