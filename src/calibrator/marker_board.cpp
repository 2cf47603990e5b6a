// The stereo branch's first hypothesis on a board that carries markers: the
// pose their corners give in both images, refined with the hole rims.

#include "calibrator/camera_attempt.hpp"

#include "camera/marker_corner_noise.hpp"
#include "camera/marker_detection.hpp"
#include "camera/marker_pose.hpp"
#include "camera/stereo_marker_pose.hpp"
#include "verify/stereo_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace l2s::detail {

std::optional<CameraAttempt> board_from_markers(const CameraFrame& f, std::string& why) {
  const MarkerLayout& layout = *f.target.markers;
  auto left = find_target_markers(f.left_gray, layout), right = find_target_markers(f.right_gray, layout);
  std::ostringstream text;
  text << left.size() << " of the target's " << layout.ids.size() << " markers in the left image, " << right.size()
       << " in the right";
  const StereoMarkerPose all = stereo_pose_from_markers(left, right, layout, f.cameras);
  if (!all.found) {
    why = text.str() + ": no board pose facing the camera";
    return std::nullopt;
  }
  // The limit follows the corners' noise in this image and the markers'
  // placement tolerance at the board's range; a marker glued off its place
  // while the others agree is left out of both images.
  const double corner_sigma = marker_corner_sigma(f.left_gray, left, MarkerLayout::dictionary_bits(layout.dictionary));
  const double limit = marker_rms_limit_px(f.params.mono, f.cameras.left.fx(), all.T_camera_board.translation().norm(),
                                           corner_sigma);
  int left_out = -1;
  const StereoMarkerPose pose = robust_stereo_pose_from_markers(left, right, layout, f.cameras, all, limit,
                                                                3.0 * std::sqrt(2.0) * corner_sigma, left_out);
  if (left_out >= 0) {
    const auto drop = [left_out](const MonoBoardDetector::Marker& m) { return m.id == left_out; };
    left.erase(std::remove_if(left.begin(), left.end(), drop), left.end());
    right.erase(std::remove_if(right.begin(), right.end(), drop), right.end());
    text << "; marker " << left_out << " left out (off its place while the others agree)";
  }
  const double rms = std::max(pose.rms_left_px, pose.rms_right_px);
  if (rms > limit) {
    text.precision(2);
    text << ": their corners fit one board pose only to " << std::fixed << rms << " px (limit " << limit << " px)";
    why = text.str();
    return std::nullopt;
  }
  CameraAttempt attempt;
  attempt.T_camera_board = pose.T_camera_board;
  attempt.markers = static_cast<int>(left.size());
  attempt.refined = BoardPoseRefiner(f.params.board_refiner)
                        .refine(f.left, f.right, f.cameras, f.target, pose.T_camera_board,
                                corner_observations(left, layout), corner_observations(right, layout),
                                f.params.mono.marker_weight);
  if (attempt.refined->converged) {
    text << ", refined on the rims";
  } else {
    text << "; the rims did not converge there (" << attempt.refined->reason << "): the markers' pose kept";
    attempt.refined.reset();
  }
  const Eigen::Isometry3d& T = attempt.refined ? attempt.refined->T_camera_board : attempt.T_camera_board;
  StereoEvidenceParams evidence_params;
  evidence_params.max_depth = f.params.stereo.max_depth;
  const BoardEvidence evidence =
      stereo_evidence(f.left_gray, f.right_gray, f.cameras, T, f.target, f.params.camera_verifier, evidence_params);
  for (int h = 0; h < 4; ++h)
    if (evidence.hole_blocked[h] >= f.params.camera_verifier.min_samples &&
        evidence.hole_blocked[h] > evidence.hole_open[h]) {
      why = text.str() + "; the images show hole " + std::to_string(h) + " covered where their pose puts it";
      return std::nullopt;
    }
  why = text.str();
  return attempt;
}

}  // namespace l2s::detail
