// Calibrator::result()'s registration over board poses with a sparse stream:
// a ring-free lidar gives one set of centres per window of sweeps (at the
// window's last frame), the camera one per frame. The poses are grouped on
// the camera's frames and the window's centres join the pose they lie in or
// next to. Before, the window's single set made no static stretch of its own
// and the result said "lidar centres do not cluster: only 0 frames added".

#include "calibrator/pose_registration.hpp"

#include <gtest/gtest.h>

namespace l2s {
namespace {

/// The target's hole centres 3 m ahead of a sensor (x forward), shifted by `offset`.
HoleCenters board_centres(const Eigen::Vector3d& offset) {
  const auto holes = Target().hole_centers();
  HoleCenters out;
  for (int h = 0; h < 4; ++h) out[h] = Eigen::Vector3d(3.0, -holes[h].x(), holes[h].y()) + offset;
  return out;
}

std::vector<FrameReport> static_board_frames(int count, int camera_frames, int lidar_frame) {
  std::vector<FrameReport> frames(count);
  const Eigen::Vector3d lidar_offset(0.0, 0.0, 0.0), camera_offset(0.1, 0.2, -0.05);
  for (int i = 0; i < count; ++i) {
    frames[i].camera.found = i < camera_frames;
    if (frames[i].camera.found) frames[i].camera.centers = board_centres(camera_offset);
    frames[i].lidar.found = i == lidar_frame;
    if (frames[i].lidar.found) frames[i].lidar.centers = board_centres(lidar_offset);
  }
  return frames;
}

TEST(PoseRegistration, ARingFreeWindowJoinsThePoseOfItsFrames) {
  const auto frames = static_board_frames(20, 20, 19);
  Calibrator::Result result;
  ASSERT_TRUE(detail::register_poses(frames, std::nullopt, Calibrator::Params(), result)) << result.reason;
  ASSERT_EQ(result.poses_used(), 1);
  EXPECT_LT((result.T_lidar_camera.translation() - Eigen::Vector3d(-0.1, -0.2, 0.05)).norm(), 1e-9);
}

TEST(PoseRegistration, AWindowDetectedAfterTheCameraLostTheBoardJoinsTheNearestPose) {
  // The window's last images no longer show the board; its lidar centres come
  // late (result() closes the window) and lie past the camera's frames.
  const auto frames = static_board_frames(20, 14, -1);
  Calibrator::Result result;
  ASSERT_TRUE(detail::register_poses(frames, board_centres(Eigen::Vector3d::Zero()), Calibrator::Params(), result))
      << result.reason;
  EXPECT_EQ(result.poses_used(), 1);
}

}  // namespace
}  // namespace l2s
