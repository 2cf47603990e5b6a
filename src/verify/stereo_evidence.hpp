#pragma once
// Board evidence from a rectified stereo pair (private). Stereo matching says
// little about a hole: over a plain background SGM carries the board's
// disparity into it. The images themselves do: if the board were solid at a
// place, the left and right views of that place would match at the disparity
// the plane gives it. Inside a true hole the background lies at another depth
// and the views disagree; on a wall mistaken for the board they agree. Only
// places with horizontal texture give evidence (a plain surface, a smooth
// ramp or a horizontal line matches at any horizontal shift).

#include <l2s/board_verifier.hpp>
#include <l2s/camera.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace l2s::detail {

struct StereoEvidenceParams {
  int patch_radius = 3;          // [px] of the zero-mean cross-correlation window (7 x 7)
  double min_contrast = 3.0;     // [gray levels] std of both patches for a sample to count ...
  double noise_factor = 3.0;     // ... and at least this many times the image noise
  int discriminating_shift_px = 2;   // [px] a patch must stop matching itself when shifted this far ...
  double max_self_correlation = 0.6;  // ... i.e. correlate below this with its shifted self
  double consistent = 0.7;       // correlation at or above: the place lies on the plane (blocked)
  double inconsistent = 0.3;     // correlation below: it does not (open)
  double sample_step_px = 3.0;   // [px] spacing of the samples in the left image
  int max_samples = 400;         // per hole and for the outline band
};

/// `left`, `right`: rectified 8-bit gray images of `cameras`;
/// `T_camera_board` in the left optical frame. fit_rms/fit_scale are left
/// for the caller.
BoardEvidence stereo_evidence(const cv::Mat& left, const cv::Mat& right, const StereoCamera& cameras,
                              const Eigen::Isometry3d& T_camera_board, const Target& target,
                              const BoardVerifier::Params& verifier, const StereoEvidenceParams& params = {});

}  // namespace l2s::detail
