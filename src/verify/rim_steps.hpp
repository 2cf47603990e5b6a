#pragma once
// The brightness step across a board's hole rims, summed along arcs
// (private). The rim refinement confirms a rim sample by an image edge at
// it, one sample at a time; a board of nearly the gray of what lies behind
// it, slightly blurred, has rims of ~1 gray level / px, below the image
// noise per sample, and the verifier saw none of them. Yet such a rim is one
// consistent step along tens of pixels: the mean step over an arc is many
// times its noise. The same sum on circles on the board's face around the
// holes tells a board (a smooth face, steps only at its rims) from a
// patterned wall taken for one (steps anywhere). Only that excess is
// evidence: a smooth shading ramp across a circle sums to a significant
// "step" too, on the face circles as on the rims.

#include <l2s/camera.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <limits>

namespace l2s::detail {

struct RimStepParams {
  int arcs_per_circle = 8;      // each rim (and face circle) is judged in this many arcs ...
  int samples_per_arc = 12;     // ... of this many samples
  double near_px = 2.0;         // [px] the step compares the brightness from this far ...
  double far_px = 3.0;          // ... to this far on each side of the circle (beyond the blur of the edge)
  double noise_factor = 5.0;    // an arc's mean step must exceed this many sigmas of its noise
  double pixels_per_sample = 2.0;  // [px] samples closer along the arc than this share their noise (blur, interpolation)
  double face_radius = 1.35;    // [hole radii] the face circles around each hole
};

/// Shares of arcs whose mean brightness step across the circle exceeds its
/// noise; NaN when no arc was inside an image.
struct RimSteps {
  double rims = std::numeric_limits<double>::quiet_NaN();  // on the front rims of the holes
  double face = std::numeric_limits<double>::quiet_NaN();  // on the face circles (within the board, off the holes)
};

/// `left`, `right`: rectified 8-bit gray images of `cameras`; the board at
/// `T_camera_board` (left optical frame), facing the cameras.
RimSteps rim_steps(const cv::Mat& left, const cv::Mat& right, const StereoCamera& cameras, const Target& target,
                   const Eigen::Isometry3d& T_camera_board, const RimStepParams& params = {});

}  // namespace l2s::detail
