// The check's observations from the branch traces (check_frames.hpp). It
// reads the branches' traces and runs the branches, so it lives with them,
// above the check, which sees only the observations it makes.

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
  // A ring-free lidar's detection ran on its accumulated window: a single
  // sweep of it holds too few depth edges (tens) to check against the image.
  const bool window = found && inspection.ring_free && !inspection.cloud.points.empty();
  LidarObservation out = observer.observe_lidar(window ? inspection.cloud : sweep, board);
  if (found && inspection.circles && inspection.circles->found)
    out.hole_centers.assign(inspection.circles->centers.begin(), inspection.circles->centers.end());
  return out;
}

CameraObservation observe_camera(const Image& left, const CameraInspection& inspection, bool found,
                                 const StereoCamera& cameras, const SceneObserver& observer, bool with_edges) {
  CameraObservation out;
  // The branch works in the rectified frame (raw images are rectified
  // first); the check keeps the board in the camera frame of DATASET.md,
  // where the calibrated transform lives: p_camera = R_rect_camera^T p_rect.
  Eigen::Isometry3d T_camera_rect = Eigen::Isometry3d::Identity();
  const Image& rectified_left = inspection.rectified ? inspection.rectified->left : left;
  if (inspection.rectified) T_camera_rect.linear() = inspection.rectified->R_rect_camera.transpose();
  if (found) {
    out.board_pose_refined = inspection.refined && inspection.refined->converged;
    if (out.board_pose_refined)
      out.T_camera_board = T_camera_rect * inspection.refined->T_camera_board;
    else if (inspection.T_camera_board_initial)
      out.T_camera_board = T_camera_rect * *inspection.T_camera_board_initial;
    if (inspection.board.size() >= 3) {
      out.stereo_plane = Plane(inspection.board_plane).transform(T_camera_rect.linear(), Eigen::Isometry);
      out.stereo_row_texture = observer.row_texture_share(rectified_left, inspection.board);
    }
  }
  // The whole frame's disparity: the coarse pass when the board was located
  // first (the full-resolution pass then covers its region only). Disparity
  // and depth stay in the rectified frame, as the check projects into it.
  if (inspection.located && inspection.located->stereo.found)
    out.depth = observer.observe_depth(inspection.located->stereo.disparity, cameras,
                                       inspection.located->stereo.depth_noise);
  else if (!inspection.located && inspection.stereo && inspection.stereo->found)
    out.depth = observer.observe_depth(inspection.stereo->disparity, cameras, inspection.stereo->depth_noise);
  observer.mark_texture(rectified_left, out.depth);
  // Edges of the rectified left image: the branch's own rectification when
  // it made one (the same P, so the same pixels, and no second remap).
  if (with_edges)
    out.edges = inspection.rectified
                    ? observer.observe_edges(inspection.rectified->left, inspection.rectified->cameras)
                    : observer.observe_edges(left, cameras);
  return out;
}

CheckFrame observe_frame(const LidarCloud& sweep, const Image& left, const Image& right, const StereoCamera& cameras,
                         const Target& target, const Calibrator::Params& params, const SceneObserver& observer,
                         const std::string& id) {
  LidarInspection lidar;
  CameraInspection camera;
  const BranchReport lidar_report = detail::run_lidar_branch(sweep, target, params, &lidar);
  // The rectifier's maps are built per call: a caller checking many raw
  // frames pays that once per frame, which `l2s check` can afford.
  const detail::CameraSetup setup(cameras);
  const BranchReport camera_report = detail::run_camera_branch(left, right, setup, target, params, &camera);
  CheckFrame frame;
  frame.id = id;
  frame.lidar = observe_lidar(sweep, lidar, lidar_report.found, observer);
  frame.camera = observe_camera(left, camera, camera_report.found, cameras, observer);
  return frame;
}

}  // namespace l2s
