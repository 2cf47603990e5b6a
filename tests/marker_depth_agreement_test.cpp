// The coarse stereo depth counts as the check's evidence only where it shows
// the board where its markers put it: a plane through the board's face,
// neither tilted nor shifted off it.

#include "calibrator/marker_depth_agreement.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using l2s::StereoCloud;
using l2s::Target;

/// A board 2.5 m ahead of the camera, yawed 20 deg.
Eigen::Isometry3d board_pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.1, -0.2, 2.5);
  return T;
}

/// Points of a plane `T_camera_plane` sampled on a grid over the board's
/// extent and beyond, with a depth error that alternates by `jitter`.
StereoCloud cloud_on(const Eigen::Isometry3d& T_camera_plane, double jitter = 0.0) {
  StereoCloud cloud;
  int k = 0;
  for (double x = -1.0; x <= 1.0; x += 0.02)
    for (double y = -0.7; y <= 0.7; y += 0.02, ++k) {
      Eigen::Vector3d p = T_camera_plane * Eigen::Vector3d(x, y, 0.0);
      p *= 1.0 + (k % 2 ? jitter : -jitter) / p.norm();
      cloud.points.push_back(p);
      cloud.pixels.emplace_back(0, 0);
    }
  return cloud;
}

TEST(MarkerDepthAgreement, ADepthOnTheMarkersBoardAgrees) {
  const Target target;
  const auto agreement = l2s::detail::marker_depth_agreement(cloud_on(board_pose(), 0.01), board_pose(), target);
  EXPECT_TRUE(agreement.agrees) << agreement.summary;
  EXPECT_GT(agreement.face_points, 1000);
  EXPECT_LT(agreement.tilt_deg, 0.5);
  EXPECT_LT(agreement.offset, 0.005);
}

TEST(MarkerDepthAgreement, ADepthTiltedOffTheBoardDoesNot) {
  const Target target;
  Eigen::Isometry3d tilted = board_pose();
  tilted.linear() = tilted.linear() * Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto agreement = l2s::detail::marker_depth_agreement(cloud_on(tilted), board_pose(), target);
  EXPECT_FALSE(agreement.agrees) << agreement.summary;
  EXPECT_NEAR(agreement.tilt_deg, 10.0, 0.5);
}

TEST(MarkerDepthAgreement, ADepthShiftedBehindTheBoardDoesNot) {
  const Target target;
  Eigen::Isometry3d shifted = board_pose();
  shifted.translation() *= 1.05;  // 13 cm farther along the rays
  const auto agreement = l2s::detail::marker_depth_agreement(cloud_on(shifted), board_pose(), target);
  EXPECT_FALSE(agreement.agrees) << agreement.summary;
  EXPECT_GT(agreement.offset, 0.5 * target.hole_radius);
}

TEST(MarkerDepthAgreement, AFewMatchesOnTheBoardDoNot) {
  const Target target;
  StereoCloud sparse;
  const StereoCloud full = cloud_on(board_pose());
  for (std::size_t i = 0; i < full.size(); i += 200) sparse.points.push_back(full.points[i]);
  const auto agreement = l2s::detail::marker_depth_agreement(sparse, board_pose(), target);
  EXPECT_FALSE(agreement.agrees) << agreement.summary;
  EXPECT_LT(agreement.face_points, 30);
}

}  // namespace
