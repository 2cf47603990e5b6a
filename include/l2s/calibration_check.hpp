#pragma once
// Can a transform be trusted without ground truth? A scene-level check of
// T_lidar_camera against everything the frames hold, independent of the four
// hole centres it was (perhaps) fitted to (issue 11):
//  - board consistency: the lidar board returns, moved into the camera
//    frame, must lie on the camera's board plane, and the points where the
//    lidar rings leave the board must fall on its outline and hole rims;
//  - edge alignment: the lidar's depth discontinuities of the whole scene,
//    projected into the left image, must fall on image edges; the score is
//    scanned per degree of freedom, and a right transform sits at a clear
//    peak (its offset says how far off the transform is, its width how well
//    the scene constrains that degree of freedom);
//  - depth agreement: lidar returns of the whole scene against the stereo
//    depth at their pixel;
//  - competing hypotheses: the transforms the target's symmetry allows
//    (hole labels turned by 180 deg, or 90 deg steps on a square pattern)
//    fit the centres exactly as well, so they are scored the same way. One
//    the scene supports about as well makes the result ambiguous.
// The verdict is ok, suspect or failed, with reasons.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/hole_symmetry.hpp>
#include <l2s/registrar.hpp>
#include <l2s/scene_observer.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace l2s {

/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT CalibrationCheck {
 public:
  enum class Verdict {
    Ok,       ///< the scene confirms the transform
    Suspect,  ///< something is off or too weakly observed to confirm: look at the reasons and the overlay
    Failed,   ///< the scene contradicts the transform, or cannot tell it from a symmetric alternative
  };

  struct Params {
    // --- scoring ---
    double edge_sigma_px = 2.0;      ///< [px] a lidar edge this far from an image edge scores exp(-1/2) of a hit, > 0
    int max_edge_frames = 8;         ///< frames whose edges and depth are scored (evenly spread), >= 1
    double scan_range_deg = 4.0;     ///< [deg] each degree of freedom is scanned +- this (translations: the same image motion at the edges' median depth), > 0
    double depth_tolerance = 0.05;   ///< a lidar return agrees with stereo within this share of its depth, plus 3 sigma of the stereo noise, > 0
    double outline_band = 0.03;      ///< [m] lidar board returns farther than this outside the outline (or inside a hole) count as outside, > 0
    // --- verdict: suspect beyond the first value, failed beyond the second ---
    double suspect_misalignment_deg = 0.3;  ///< [deg] image motion of the lidar edges to their best alignment (px / fx), > 0
    double failed_misalignment_deg = 1.5;   ///< [deg] >= suspect_misalignment_deg
    double suspect_roll_deg = 0.6;          ///< [deg] roll about the optical axis to the best alignment (moves pixels near the centre little), > 0
    double failed_roll_deg = 2.0;           ///< [deg] >= suspect_roll_deg
    /// [deg] How much nearer to image edges an image shift of their own
    /// brings the lidar edges off the board (Report::scene_misalignment),
    /// beyond which the board seems to have moved between the lidar sweep
    /// and the images. Looser than the misalignment: those edges are few and
    /// settle on texture and shadows (right random-scene results, within
    /// 0.4 deg, reached 0.3-1.4 deg), > 0.
    double suspect_scene_misalignment_deg = 1.0;
    double failed_scene_misalignment_deg = 3.0;  ///< [deg] >= suspect_scene_misalignment_deg
    double suspect_outline_deg = 0.25;      ///< [deg] median distance of the lidar board edges from the board's contour (px / fx), > 0
    double failed_outline_deg = 1.0;        ///< [deg] >= suspect_outline_deg
    double suspect_plane_offset = 0.015;    ///< [m] lidar board returns from the camera's board plane (its rims' pose), > 0
    double failed_plane_offset = 0.06;      ///< [m] >= suspect_plane_offset
    /// The plane offset counts only beyond this disparity [px] at the
    /// board's depth: the rims place a far board seen by a short baseline
    /// only to a few hundredths of a pixel (0.3 px is 5 cm at 3.9 m with
    /// fx B 91 px m), >= 0.
    double min_plane_offset_px = 0.3;
    /// [px] The stereo board plane against the rims' plane: a wrong target
    /// size scales the rims' depth, not the stereo's (3 % is 1.4 px for the
    /// paper's rig and board); a wrong baseline the other way round. On
    /// random scenes it was at most 0.32 px for plain and textured faces, > 0.
    double suspect_stereo_offset_px = 0.6;
    double failed_stereo_offset_px = 3.0;   ///< [px] >= suspect_stereo_offset_px
    /// [px] The suspect level instead, for a face whose texture runs along
    /// the rows (Scores::stereo_row_texture >= row_texture_share): SGBM
    /// fills it in from its surroundings, and a wood-grain face was up to
    /// 2 px off boards its rims placed right (one 3.3 px); in
    /// [suspect_stereo_offset_px, failed_stereo_offset_px]. Such a face's
    /// offset alone never fails a result.
    double row_texture_stereo_offset_px = 2.5;
    double row_texture_share = 0.3;  ///< 0..1; on random scenes wood-grain faces measured 0.2-0.9, plain and low-contrast ones at most 0.2
    double suspect_plane_tilt_deg = 1.0;    ///< [deg] lidar board against the camera's, > 0
    double failed_plane_tilt_deg = 4.0;     ///< [deg] >= suspect_plane_tilt_deg
    /// [deg] Scatter of the camera's board pose from frame to frame
    /// (Scores::pose_scatter). Right random-scene results scattered up to
    /// 0.32 deg; a wrong one (257 mm, 2.7 deg), whose every other board
    /// measure agreed, 2.1 deg, > 0.
    double suspect_pose_scatter_deg = 0.75;
    double failed_pose_scatter_deg = 4.0;  ///< [deg] >= suspect_pose_scatter_deg
    double suspect_center_offset = 0.012;   ///< [m] lidar hole centres from the camera's holes, in the board plane (a calibration's own centres agree to a few mm), > 0
    double failed_center_offset = 0.05;     ///< [m] >= suspect_center_offset
    double suspect_outside_fraction = 0.08; ///< share of lidar board returns outside the board's outline, (0, 1)
    double failed_outside_fraction = 0.3;   ///< >= suspect_outside_fraction
    double suspect_alignment_gain = 0.3;    ///< the best edge score of any scan beats this transform's by this share, (0, 1)
    double failed_alignment_gain = 0.6;     ///< >= suspect_alignment_gain
    /// The misalignment rule counts only when the best alignment near the
    /// transform beats this transform's edge score by this share
    /// (Report::misalignment_gain): below it the score is flat around the
    /// transform, and where its optimum lies is noise, [0, 1).
    double min_misalignment_gain = 0.1;
    /// ... and only when the edge score there is at least this: a weak
    /// optimum (a shadow's edge, texture) is where six degrees of freedom
    /// found a little more to lean on, not where the scene lies, 0..1.
    double min_optimum_edge_score = 0.4;
    /// ... and only when that alignment lies beyond this many half widths
    /// of the score's peak (DofPeak::offset against DofPeak::width) in at
    /// least one degree of freedom: within its peak in every one, the score
    /// cannot tell the transform from the optimum (a good random-scene
    /// result was 0.38 deg "misaligned" at 0.67 widths; wrong ones were
    /// 1.7-6.6 widths away), >= 0.
    double min_misalignment_widths = 1.0;
    /// ... and not where the board refutes that alignment and nothing else
    /// favours it: there its lidar hole centres would lie more than this
    /// from the camera's holes in the board plane, while at the transform
    /// they lie within a third of it (or the outline or plane would turn
    /// suspect there; the plane not for a result fitted to one pose of this
    /// board, whose plane agrees by construction), and neither the edges off the board
    /// (Report::scene_misalignment, which an unsynchronised board makes)
    /// nor the lidar depths off the board (Scores::depth_tilt) agree better
    /// there. Texture then drew the edges: mortar joints close behind a
    /// low-contrast board can pull the edges' best alignment a degree or
    /// more from a right result, where the hole centres lie centimetres
    /// apart instead of fractions of a millimetre. A tilted camera board
    /// moves the centres at the truth too, which the depth guard catches,
    /// [m] > 0.
    double refuting_center_offset = 0.006;
    /// Share of the lidar returns of the scene whose depth agrees with
    /// stereo below which the result is suspect / failed: a right transform
    /// has most agree (0.75-1 on the randomised scenes), a wrong one puts
    /// returns on pixels of other surfaces, 0..1.
    double suspect_depth_agreement = 0.6;
    double failed_depth_agreement = 0.3;  ///< <= suspect_depth_agreement
    /// The roll rule counts only when the roll scan peaks this clearly
    /// (prominence): a roll moves the edges near the image centre little, so
    /// a true one raises the score by little, but its optimum is sharp; and,
    /// like the misalignment rule, only at an edge score of
    /// min_optimum_edge_score there, 0..1.
    double min_roll_prominence = 0.5;
    double suspect_depth_tilt_deg = 2.0;    ///< [deg] lidar against stereo depth off the board (coarse stereo alone tilts up to ~1.1 deg with the default preset, 1.64 deg with the paper preset on the nine settings), > 0
    /// [deg] >= suspect_depth_tilt_deg. High: coarse stereo on a plain or
    /// dark wall tilts by 2-6 deg on its own (randomised scenes, results
    /// within 0.2 deg of the truth), so this evidence alone makes a result
    /// suspect, and fails it only when the tilt is beyond such noise.
    double failed_depth_tilt_deg = 10.0;
    double suspect_depth_bias = 0.05;   ///< lidar against stereo depth, as a share of the depth (coarse stereo alone is off by up to ~2 % far away), > 0
    double failed_depth_bias = 0.15;    ///< >= suspect_depth_bias
    int min_edge_points = 60;         ///< fewer lidar edges seen in the images is too little evidence (suspect), >= 1
    int min_scene_edge_points = 12;   ///< edges off the board needed to align them on their own, >= 1
    double min_prominence = 0.15;     ///< rx and ry must peak at least this far above the scan's median (share of the peak), else suspect, 0..1
    double hypothesis_margin = 0.06;  ///< an alternative needs this much more scene support to be preferred; closer, the result is ambiguous, > 0
    /// [deg] When the scene cannot tell the transform from a symmetric
    /// alternative (a board alone, as a solid-state lidar's cloud cropped
    /// to it), the sensors' mounting still can: a lidar's +z is its up
    /// (a spinning lidar's axis, REP 103) and an image's rows run down. If
    /// the lidar's up lies within this angle of the image's up under the
    /// transform, and at least twice as far under every alternative the
    /// scene supports as well, the result is suspect, not failed; 0: never.
    double upright_deg = 30.0;

    void validate() const;  ///< throws ParamError naming the field
  };

  /// Scores of one transform. NaN where no frame gave the evidence.
  struct Scores {
    static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    double edge_score = 0.0;        ///< share of the lidar edges seen in the images that lie on image edges (kernel-weighted), 0..1
    double scene_edge_score = 0.0;  ///< the same for the edges off the board (what tells a turned board apart)
    int edge_points = 0;            ///< lidar edges scored (in the image under this transform)
    int scene_edge_points = 0;      ///< of which off the board
    double depth_agreement = kNaN;  ///< share of lidar returns with stereo depth at their pixel that agree with it, 0..1
    int depth_points = 0;           ///< lidar returns compared with stereo
    double depth_bias = kNaN;       ///< median (lidar - stereo) / stereo depth of the returns within 20 %: a scale error (target size, baseline) or a shift along the view
    double depth_tilt = kNaN;       ///< [rad] off the board, lidar depth against stereo tilts across the image by this beyond what a disparity bias of one matching sigma can tilt on that surface: a rotation error about the camera's x / y axes, whatever the translation
    double depth_tilt_sigma = kNaN; ///< [rad] standard error of depth_tilt from frame to frame (delete-one-frame jackknife; NaN under 3 frames); the verdict grades depth_tilt less twice this
    double depth_tilt_texture = kNaN; ///< share of the tilt's plane (the largest off the board) on stereo texture (DepthMap::textured); under 0.15 the tilt is not measured (NaN): stereo there is SGBM's fill-in
    double plane_offset = kNaN;     ///< [m] median distance of lidar board returns from the camera's board plane, the pose its rims give (+: in front)
    double plane_offset_px = kNaN;  ///< [px] that distance as disparity at the board's depth (fx B offset / z^2)
    double stereo_offset = kNaN;    ///< [m] the stereo board plane from the rims' plane at the board's centre (+: in front), median over frames: a scale error of the camera (target size, baseline) or stereo's own bias
    double stereo_offset_px = kNaN; ///< [px] that distance as disparity at the board's depth
    double stereo_row_texture = kNaN;  ///< share of the board's stereo points whose texture runs along the rows (SceneObserver::row_texture_share), median over frames
    double plane_spread = kNaN;     ///< [m] robust sigma of those distances
    double plane_tilt = kNaN;       ///< [rad] lidar board plane (in the camera frame) against the camera's board pose: the rotation between them, median over frames (per component, so noise averages out)
    /// [rad] How much that rotation scatters from frame to frame (robust
    /// sigma per component, their length; NaN with fewer than 3 frames). The
    /// lidar's board plane rests on hundreds of returns, so this is the
    /// camera's board pose turning between frames of a static board: a
    /// detection the scene makes unstable, whose error the result may carry
    /// whole (the plane tilt cannot show it: the fit made the boards agree).
    double pose_scatter = kNaN;
    double outline_px = kNaN;       ///< [px] median distance, in the image, of lidar board edges from the outline and hole rims
    double outside_fraction = kNaN; ///< share of lidar board returns outside the board (or inside a hole)
    /// [m] In the board plane, the median offset of the lidar hole centres
    /// from the nearest hole of the camera's board pose, over all frames
    /// (its length). Labels play no part, so a symmetric alternative
    /// scores the same; it sees what the edges see poorly: a ring lidar
    /// gives no horizontal edges, so a shift along the rings' normal moves
    /// little but the centres.
    double center_offset = kNaN;
    double support = 0.0;           ///< scene support, what hypotheses are compared by: edge_score + depth_agreement + (1 - outside_fraction) at the best alignment of the edges near the transform, of those there is evidence for, 0..3
  };

  /// How the edge score peaks when one degree of freedom is perturbed
  /// (rotations about the camera's axes through its centre, translations along them).
  struct DofPeak {
    std::string name;         ///< rx, ry, rz, tx, ty, tz
    bool rotation = true;     ///< offset and width in [rad], else [m]
    double offset = 0.0;      ///< the best alignment near the checked transform (all six climbed together), relative to it
    double width = 0.0;       ///< half width at half height of the score along this degree of freedom there (the scan's reach: no peak)
    double prominence = 0.0;  ///< peak height above the scan's median, as a share of the peak, 0..1
    double best_offset = 0.0; ///< where a scan along this degree of freedom from there scores highest (a side lobe or, for a wrong transform, the right place)
    double best_gain = 0.0;   ///< 1 - score at `offset` / score at `best_offset`, 0..1
  };

  /// A transform the target's symmetry allows, scored like the checked one.
  struct Alternative {
    std::string name;  ///< e.g. "camera labels turned 180 deg"
    int degrees = 0;   ///< the turn of the camera's hole labels
    HolePermutation relabel{{0, 1, 2, 3}};  ///< camera centroids relabelled this way give it
    Eigen::Isometry3d T_lidar_camera = Eigen::Isometry3d::Identity();
    double residual_rms = 0.0;  ///< [m] its centre fit (when re-registered)
    double up_angle = 0.0;      ///< [rad] between the lidar's +z and the image's up (-y) under it
    Scores scores;
  };

  struct Report {
    Verdict verdict = Verdict::Failed;
    std::vector<std::string> reasons;  ///< why not ok, most serious first; empty when ok
    Scores scores;                     ///< of the checked transform
    std::array<DofPeak, 6> peaks;      ///< rx, ry, rz, tx, ty, tz
    double misalignment_px = 0.0;      ///< [px] mean motion of the lidar edges in the image from this transform to the best alignment near it
    double misalignment = 0.0;         ///< [rad] the same as an angle (px / fx): how far the overlay is off
    /// [rad] For the edges off the board alone (NaN with too few): how much
    /// nearer to image edges (median, px / fx) an image shift of their own
    /// brings them, from the best alignment of all. When the board aligns but
    /// the rest of the scene does not, the board moved between the lidar
    /// sweep and the images (unsynchronised sensors) and the fit followed it.
    double scene_misalignment = std::numeric_limits<double>::quiet_NaN();
    double alignment_gain = 0.0;       ///< the largest best_gain of the six scans: a better alignment farther away, 0..1
    /// How much better the edges score at their best alignment near this
    /// transform than at the transform itself (1 - this score / that one),
    /// 0..1: below min_misalignment_gain the score is flat around the
    /// transform and where its optimum lies is noise.
    double misalignment_gain = 0.0;
    double optimum_edge_score = 0.0;   ///< edge score at that best alignment, 0..1
    /// The board's measurements and the depths off it (Scores' board and
    /// depth fields) at that best alignment, when there are board frames.
    /// Where the board agrees with this transform but would not agree there,
    /// and nothing else favours it, the edges were drawn by texture (a
    /// repetitive background), and the misalignment does not count
    /// (Params::refuting_center_offset).
    std::optional<Scores> optimum_board;
    double median_depth = 0.0;         ///< [m] of the scored lidar edges, camera frame
    std::vector<Alternative> alternatives;
    int preferred = -1;      ///< an alternative the scene supports clearly better (index), else -1
    bool ambiguous = false;  ///< an alternative is supported about as well as the checked transform
    double up_angle = 0.0;   ///< [rad] between the lidar's +z and the image's up (-y) under the checked transform
    /// Ambiguous, but only the checked transform stands both sensors
    /// upright (Params::upright_deg): suspect rather than failed.
    bool upright_only = false;
    int frames = 0;          ///< frames given
    int board_frames = 0;    ///< with board returns and a camera board pose
    int edge_frames = 0;     ///< whose edges were scored
    int depth_frames = 0;    ///< with stereo depth
    double milliseconds = 0.0;  ///< [ms] wall time of check()
  };

  CalibrationCheck(StereoCamera cameras, Target target);
  /// Throws ParamError for invalid params or target.
  CalibrationCheck(StereoCamera cameras, Target target, Params params);

  /// Checks T_lidar_camera (p_lidar = T * p_camera) against `frames`.
  /// `alternatives` are scored beside it (their scores are filled in); when
  /// empty, they are made from the target's symmetries about the board pose
  /// of the first frame with one (board_alternatives). Never throws on bad data.
  Report check(const std::vector<CheckFrame>& frames, const Eigen::Isometry3d& T_lidar_camera,
               std::vector<Alternative> alternatives = {}) const;

  const Params& params() const { return params_; }

 private:
  StereoCamera cameras_;
  Target target_;
  Params params_;
};

/// The alternatives of a fit to hole centroids: the camera centroids
/// relabelled by each non-identity symmetry of the target, registered again.
L2S_EXPORT std::vector<CalibrationCheck::Alternative> relabelled_alternatives(const HoleCenters& lidar, const HoleCenters& camera,
                                                                   const Target& target, const Registrar& registrar);

/// The same transforms without centroids: T turned by each non-identity
/// symmetry of the target about the board's centre and normal (camera frame).
L2S_EXPORT std::vector<CalibrationCheck::Alternative> board_alternatives(const Eigen::Isometry3d& T_lidar_camera,
                                                              const Eigen::Isometry3d& T_camera_board,
                                                              const Target& target);

/// "ok", "suspect", "failed".
L2S_EXPORT const char* verdict_name(CalibrationCheck::Verdict verdict);

/// A readable report: verdict and reasons, scores, peaks and alternatives. Ends with a newline.
L2S_EXPORT std::string describe(const CalibrationCheck::Report& report);

}  // namespace l2s
