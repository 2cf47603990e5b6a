// The check's observations from the branch traces (check_frames.hpp).

#include <l2s/check_frames.hpp>

#include "calibrator/branches.hpp"

namespace l2s {

LidarObservation observe_lidar(const LidarCloud& sweep, const LidarInspection& inspection, bool found,
                               const SceneObserver& observer) {
  std::vector<Eigen::Vector3d> board;
  if (found && inspection.plane && inspection.candidate >= 0) {
    const auto& inliers = inspection.plane->candidates[inspection.candidate].inliers;
    board.reserve(inliers.size());
    for (const std::size_t i : inliers) board.push_back(inspection.cloud.points[i]);
  }
  return observer.observe_lidar(sweep, board);
}

CameraObservation observe_camera(const Image& left, const CameraInspection& inspection, bool found,
                                 const StereoCamera& cameras, const SceneObserver& observer, bool with_edges) {
  CameraObservation out;
  if (found) {
    if (inspection.refined && inspection.refined->converged)
      out.T_camera_board = inspection.refined->T_camera_board;
    else if (inspection.T_camera_board_initial)
      out.T_camera_board = *inspection.T_camera_board_initial;
    if (inspection.board.size() >= 3) out.stereo_plane = inspection.board_plane;
  }
  // The whole frame's disparity: the coarse pass when the board was located
  // first (the full-resolution pass then covers its region only).
  if (inspection.located && inspection.located->stereo.found)
    out.depth = observer.observe_depth(inspection.located->stereo.disparity, cameras,
                                       inspection.located->stereo.depth_noise);
  else if (!inspection.located && inspection.stereo && inspection.stereo->found)
    out.depth = observer.observe_depth(inspection.stereo->disparity, cameras, inspection.stereo->depth_noise);
  if (with_edges) out.edges = observer.observe_edges(left, cameras);
  return out;
}

CheckFrame observe_frame(const LidarCloud& sweep, const Image& left, const Image& right, const StereoCamera& cameras,
                         const Target& target, const Calibrator::Params& params, const SceneObserver& observer,
                         const std::string& id) {
  LidarInspection lidar;
  CameraInspection camera;
  const BranchReport lidar_report = detail::run_lidar_branch(sweep, target, params, &lidar);
  const BranchReport camera_report = detail::run_camera_branch(left, right, cameras, target, params, &camera);
  CheckFrame frame;
  frame.id = id;
  frame.lidar = observe_lidar(sweep, lidar, lidar_report.found, observer);
  frame.camera = observe_camera(left, camera, camera_report.found, cameras, observer);
  return frame;
}

}  // namespace l2s
