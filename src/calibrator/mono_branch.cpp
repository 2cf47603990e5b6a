#include "calibrator/branches.hpp"

namespace l2s::detail {

BranchReport run_mono_branch(const Image& left, const MonoBoardDetector& detector) {
  const MonoBoardDetector::Result detected = detector.detect(left);
  BranchReport report;
  report.found = detected.found;
  report.failed_stage = detected.failed_stage;
  report.reason = detected.reason;
  report.markers = static_cast<int>(detected.markers.size());
  report.note = detected.note;
  report.marker_placements = detected.placements;
  if (!detected.found) return report;
  report.centers = detected.centers;
  report.rim_rms_px = detected.rim_rms_px;
  report.hole_radius = detector.target().hole_radius;
  // The check's view of the frame, should one be run: the board pose.
  CameraObservation observation;
  observation.T_camera_board = detected.T_camera_board;
  observation.board_pose_refined = detected.rim_rms_px > 0.0;
  report.observation = std::make_shared<const CameraObservation>(std::move(observation));
  return report;
}

}  // namespace l2s::detail
