// The board pose from its markers in both rectified images, on rendered
// frames against the simulator's truth: all markers in both images; the
// right image alone (its pose carried into the left frame by the baseline);
// one marker in each image, where neither image alone has the board's tilt.

#include <l2s/sim/simulation.hpp>

#include "camera/cv_image.hpp"
#include "camera/marker_detection.hpp"
#include "camera/marker_pose.hpp"
#include "camera/stereo_marker_pose.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace l2s {
namespace {

constexpr double kDeg = 3.141592653589793 / 180.0;

/// A marked board rendered by the paper's rig, its markers found in both
/// rectified images, and the truth.
struct MarkedFrame {
  Target target;
  StereoCamera cameras;
  std::vector<MonoBoardDetector::Marker> left, right;
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();  ///< T_camera_board, left rectified frame

  static MarkedFrame render(int setting) {
    sim::SimulationConfig config = sim::SimulationConfig::paper(setting, "vlp16");
    config.frames = 1;
    config.seed = 11;
    config.target = Target::with_default_markers();
    const sim::DatasetSimulator simulator(config);
    const sim::SimulatedFrame frame = simulator.frame(0);
    MarkedFrame out;
    out.target = config.target;
    out.cameras = simulator.cameras();
    out.left = detail::find_target_markers(detail::gray_mat(frame.left, "left"), *config.target.markers);
    out.right = detail::find_target_markers(detail::gray_mat(frame.right, "right"), *config.target.markers);
    out.truth = config.rig.T_cambody_optical(0).inverse() * simulator.board_pose().T_cambody_board();
    return out;
  }
};

void expect_near_truth(const detail::StereoMarkerPose& pose, const Eigen::Isometry3d& truth, double max_m,
                       double max_deg) {
  ASSERT_TRUE(pose.found);
  EXPECT_LT((pose.T_camera_board.translation() - truth.translation()).norm(), max_m) << "[m]";
  const double angle = Eigen::AngleAxisd(pose.T_camera_board.linear().transpose() * truth.linear()).angle();
  EXPECT_LT(angle / kDeg, max_deg) << "[deg]";
}

TEST(StereoMarkerPose, AllMarkersInBothImagesGiveTheTruePose) {
  for (const int setting : {1, 3}) {
    SCOPED_TRACE(setting);
    const MarkedFrame f = MarkedFrame::render(setting);
    ASSERT_EQ(f.left.size(), 4u);
    ASSERT_EQ(f.right.size(), 4u);
    const auto pose = detail::stereo_pose_from_markers(f.left, f.right, *f.target.markers, f.cameras);
    expect_near_truth(pose, f.truth, 0.005, 0.1);
    EXPECT_EQ(pose.left_corners, 16);
    EXPECT_EQ(pose.right_corners, 16);
    EXPECT_LT(pose.rms_left_px, 0.3);
    EXPECT_LT(pose.rms_right_px, 0.3);
  }
}

// The right camera sits one baseline to the right: the pose its markers
// give is carried into the left frame.
TEST(StereoMarkerPose, TheRightImageAloneGivesThePoseInTheLeftFrame) {
  const MarkedFrame f = MarkedFrame::render(1);
  const auto pose = detail::stereo_pose_from_markers({}, f.right, *f.target.markers, f.cameras);
  expect_near_truth(pose, f.truth, 0.01, 0.2);
  EXPECT_EQ(pose.left_corners, 0);
  EXPECT_EQ(pose.rms_left_px, 0.0);
}

// One small marker per image (the others covered): each image alone has its
// four corners 0.2 m apart, which hold the board's tilt poorly; two markers
// a board's width apart, one in each image, hold it through the baseline.
TEST(StereoMarkerPose, OneMarkerInEachImageHoldTheBoardTogether) {
  const MarkedFrame f = MarkedFrame::render(1);
  const std::vector<MonoBoardDetector::Marker> left_one{f.left.front()}, right_one{f.right.back()};
  const auto together = detail::stereo_pose_from_markers(left_one, right_one, *f.target.markers, f.cameras);
  expect_near_truth(together, f.truth, 0.01, 0.4);
  const auto left_alone = detail::pose_from_markers(left_one, *f.target.markers, f.cameras.left);
  const double alone_deg =
      Eigen::AngleAxisd(left_alone.T_camera_board.linear().transpose() * f.truth.linear()).angle() / kDeg;
  const double together_deg =
      Eigen::AngleAxisd(together.T_camera_board.linear().transpose() * f.truth.linear()).angle() / kDeg;
  EXPECT_LT(together_deg, alone_deg) << "one marker alone holds the tilt worse";
}

TEST(StereoMarkerPose, FewerThanFourCornersGiveNoPose) {
  const MarkedFrame f = MarkedFrame::render(1);
  EXPECT_FALSE(detail::stereo_pose_from_markers({}, {}, *f.target.markers, f.cameras).found);
  MonoBoardDetector::Marker unknown = f.left.front();
  unknown.id = 999;  // not the target's
  EXPECT_FALSE(detail::stereo_pose_from_markers({unknown}, {}, *f.target.markers, f.cameras).found);
}

}  // namespace
}  // namespace l2s
