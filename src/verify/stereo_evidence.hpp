#pragma once
// Board evidence from a rectified stereo pair (private). Stereo matching says
// little about a hole: over a plain background SGM carries the board's
// disparity into it. The images themselves do: if the board were solid at a
// place, the left and right views of that place would match at the disparity
// the plane gives it. Inside a true hole the background lies at another
// depth and matches at another disparity; on a wall mistaken for the board
// the plane's disparity wins. Only places that match one disparity clearly
// give evidence (a plain surface, a smooth ramp, a horizontal line or a
// periodic texture match at several). A repetitive background far behind a
// hole can still match one period away, at the plane's disparity, where its
// true disparity is beyond the search or hidden from the right view; such a
// hole's inside does not look like the board's face around it, and the
// verifier is told so (BoardEvidence::hole_look_difference).

#include <l2s/board_verifier.hpp>
#include <l2s/camera.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace l2s::detail {

struct StereoEvidenceParams {
  int patch_radius = 3;          // [px] of the zero-mean cross-correlation window (7 x 7)
  double min_contrast = 3.0;     // [gray levels] std of the left patch for a sample to count ...
  double noise_factor = 3.0;     // ... and at least this many times the image noise
  int search_behind_px = 40;     // [px] disparities searched behind the plane (background through a hole) ...
  int search_front_px = 12;      // ... and in front of it
  double max_depth = 10.0;       // [m] the working range's far end: a place that looks consistent is also searched that far behind ...
  int max_search_behind_px = 320;  // [px] ... up to this many disparities (cost)
  int exclusion_px = 2;          // [px] shifts this close to the plane's are the plane's own peak
  double consistent = 0.7;       // correlation of a clear match
  double margin = 0.15;          // a clear winner beats the other side's best by this
  double sample_step_px = 3.0;   // [px] spacing of the samples in the left image
  int max_samples = 150;         // per hole and for the outline band
  double face_band = 0.06;       // [m] the board's face this wide around each rim is compared with the hole's inside
};

/// `left`, `right`: rectified 8-bit gray images of `cameras`;
/// `T_camera_board` in the left optical frame. fit_rms/fit_scale are left
/// for the caller.
BoardEvidence stereo_evidence(const cv::Mat& left, const cv::Mat& right, const StereoCamera& cameras,
                              const Eigen::Isometry3d& T_camera_board, const Target& target,
                              const BoardVerifier::Params& verifier, const StereoEvidenceParams& params = {});

}  // namespace l2s::detail
