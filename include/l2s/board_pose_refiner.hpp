#pragma once
// Sub-pixel refinement of the board pose from the hole rims in both images.
// Aligns the projected silhouettes of the four apertures (front and back rim
// circles of each hole) with the image edges by robust Gauss-Newton.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace l2s {

/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT BoardPoseRefiner {
 public:
  struct Params {
    int samples_per_rim = 360;     ///< points on each rim circle (front and back); ~1 per px of rim at 3 m, 16..2000
    double search_range_px = 6.0;  ///< [px] first round's edge search along the rim normal, +-, 1..30
    double final_search_range_px = 2.0;  ///< [px] the range halves each round down to this, so a nearby parallel edge (e.g. the other rim) cannot capture samples once aligned, 1..search_range_px
    double search_step_px = 0.25;  ///< [px] spacing of the gradient samples on the search line; the 3-point parabolic peak fit is biased by a fraction of the spacing (0.5 px left ~0.5 mm of depth per hole at 3.5 m), 0.1..2
    double min_rim_separation_px = 3.0;  ///< [px] back-rim samples closer than this to the front rim's projection are dropped: the two edges (hole wall between) blend and bias the peak, 0..10
    /// When the refinement fails taking the strongest edge near each rim,
    /// try again taking the first edge met coming from the board's side (its
    /// face, or a back rim's wall): a textured background seen through the
    /// holes (bricks, tiles) has edges next to the rims that can be stronger
    /// than a low-contrast rim
    bool first_edge_from_board = true;
    double min_edge_strength = 6.0;  ///< [gray levels / px] weakest gradient accepted as the rim on a board of ordinary contrast, >= 0
    /// ... and when the refinement fails with it, on a low-contrast board (a
    /// gray board before a gray wall, slightly blurred: rims of 3-5 gray
    /// levels / px) it is tried again with the threshold lowered to this
    /// fraction of the rims' own gradient (the median over rim samples of the
    /// strongest gradient within the first search range at the initial
    /// pose), 0..1
    double rim_contrast_fraction = 0.4;
    /// ... but never below this many sigmas of the gradient's response to the
    /// image's own noise (estimated per call), so noise is not taken for rims, >= 0
    double edge_noise_factor = 5.0;
    double huber_px = 0.5;         ///< [px] Huber threshold of the robust weights, > 0
    int max_iterations = 12;       ///< search-and-fit rounds, >= 1
    int gauss_newton_steps = 3;    ///< Gauss-Newton steps per round (edges fixed), >= 1
    double image_margin_px = 4.0;  ///< [px] samples closer than this to the border are skipped, >= 0
    double converged_rotation = 2e-5;     ///< [rad] a round moving less than this ...
    double converged_translation = 2e-5;  ///< [m] ... and this has converged
    double converged_step_rms_fraction = 0.25;  ///< also converged once a round (final search range) moves no rim sample by more than this fraction of the edge rms, with the step shrinking; 0 disables, 0..1
    double min_edge_fraction = 0.8;  ///< ... and only when at least this fraction of the searched rim samples found a strong edge (wall texture alone gives far fewer), 0..1
    bool use_right_image = true;   ///< also fit the right image (needed for depth)
    int min_samples = 40;          ///< fewer edge samples than this fails, >= 7
    double max_rms_px = 1.0;       ///< [px] converged only if the final rms is below this, > 0
    /// Once the rims converged, fit again with the board's outer edges added
    /// (front and back face, as with the rims): its sides lie two to three
    /// times farther apart than the holes, so the disparity along them pins
    /// the board's tilt, which the hole pattern alone leaves to a few
    /// hundredths of a pixel of disparity (0.5 deg at 2.5 m with fx B = 53 px m)
    bool fit_board_outline = true;
    int outline_samples = 720;           ///< points on the outline per face (front, back), 16..20000
    double outline_corner_gap = 0.03;    ///< [m] no outline samples this close to a corner, >= 0
    double min_outline_share = 0.6;      ///< [0..1] the outline is kept only when this share of its edge samples fit (within 1 px; the rest is hidden or lost against its background), ...
    double max_outline_rms_px = 0.35;    ///< [px] ... those fit this well, > 0
    double max_outline_rim_growth = 1.25;  ///< ... and the rims' rms grows by at most this factor, >= 1

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  struct Result {
    bool converged = false;   ///< refinement converged with enough samples and small rms
    std::string reason;       ///< why not, when !converged
    Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();  ///< refined pose (left optical frame)
    HoleCenters centers{};    ///< [m] hole centres on the front face, left optical frame, enum Hole order
    double rms_px = 0.0;      ///< [px] rms normal distance of the used samples, last round
    int samples = 0;          ///< edge samples used in the last round (both images)
    int iterations = 0;       ///< search-and-fit rounds run
    double edge_fraction = 0.0;  ///< share of the rim samples searched when the sample set was last chosen that found a strong edge (last round)
    double last_step_px = 0.0;   ///< [px] largest image motion of a used sample in the last round
    double edge_strength = 0.0;  ///< [gray levels / px] the weakest gradient accepted as a rim (min_edge_strength, or the lowered one when the retry converged)
    bool edges_from_board_side = false;  ///< the edges were the first from the board's side, not the strongest (first_edge_from_board's retry)
    /// Share of samples on circles of 1.35 hole radii (the board's face
    /// around each hole) that find an edge of that strength at the final
    /// pose: texture, not rims. A true board's face is much smoother than its
    /// rims are sharp; a patch of patterned wall taken for the board is not.
    double face_edge_fraction = 0.0;
    /// The outline stage (Params::fit_board_outline): whether the pose and
    /// centres are those of the rims and outline together, and if not why
    /// (empty when the stage did not run). The other fields stay the rims'.
    bool outline_used = false;
    std::string outline_reason;
    int outline_samples = 0;      ///< outline edge samples of that fit (both images, within 1 px of it)
    double outline_rms_px = 0.0;  ///< [px] their rms normal distance
    /// [px] The outline's edges in the right image lie this far (along x)
    /// from where the rims' disparity puts them, fitted with the pose: the
    /// outline then holds the board's tilt but not its range, where a board
    /// edge against its background is found with another bias than a rim
    double outline_disparity_bias_px = 0.0;
    /// [m] ... and its sides (x) and its top and bottom edges (y) lie this
    /// much farther out than target.yaml's board size puts them (likewise
    /// fitted, for the same reason: the outline's apparent size would set the
    /// range; and a board is rarely cut to the millimetre)
    Eigen::Vector2d outline_dilation = Eigen::Vector2d::Zero();
  };

  // `Stage(Params = {})` does not compile with GCC while Params has default
  // member initializers (they are parsed only once the outer class is complete).
  BoardPoseRefiner() : BoardPoseRefiner(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit BoardPoseRefiner(Params params);
  const Params& params() const { return params_; }

  /// `left`, `right`: rectified 8-bit images (gray or BGR; a BGR pair whose
  /// gray alignment fails is aligned again in colour, each rim sample taking
  /// its strongest channel); `T_camera_board`:
  /// initial pose, board frame as in target.hpp. Throws ParamError for an
  /// invalid target, InputError naming the image when one is unusable or its
  /// size differs from the other's or its camera's.
  Result refine(const Image& left, const Image& right, const StereoCamera& camera,
                const Target& target, const Eigen::Isometry3d& T_camera_board) const;

  /// A board point seen at a known pixel (a marker corner), fitted together with the rims.
  struct PointObservation {
    Eigen::Vector3d X_board;  ///< [m] board frame
    Eigen::Vector2d pixel;    ///< [px] in the rectified image
  };

  /// One rectified image (a mono camera): the rims of that view (use_right_image
  /// is ignored) and `points`, each of whose image coordinates weighs as much
  /// as `point_weight` rim samples (>= 0; ParamError otherwise). A single view
  /// sees the depth and tilt of the small hole pattern weakly through the
  /// rims' size and shape; points far apart (the markers' corners) hold them.
  Result refine(const Image& image, const CameraInfo& camera, const Target& target,
                const Eigen::Isometry3d& T_camera_board, const std::vector<PointObservation>& points = {},
                double point_weight = 1.0) const;

  /// A rectified pair with points seen in each image (the markers' corners
  /// in both): one board pose fitted to the rims of both views and to the
  /// points, each of whose image coordinates weighs as much as
  /// `point_weight` rim samples (>= 0; ParamError otherwise). The rims of
  /// small holes hold the board's tilt weakly; corners spread over the
  /// board hold it.
  Result refine(const Image& left, const Image& right, const StereoCamera& camera, const Target& target,
                const Eigen::Isometry3d& T_camera_board, const std::vector<PointObservation>& left_points,
                const std::vector<PointObservation>& right_points, double point_weight = 1.0) const;

 private:
  Result refine_with_anchors(const Image& left, const Image& right, const StereoCamera& camera, const Target& target,
                             const Eigen::Isometry3d& T_camera_board, const std::vector<PointObservation>& left_points,
                             const std::vector<PointObservation>& right_points, double point_weight) const;

  Params params_;
};

}  // namespace l2s
