#pragma once
// What the stereo camera branch (camera_branch.cpp) tries on one pair: the
// stages of one board hypothesis, the pair they run on, and the hypothesis
// the board's markers give (marker_board.cpp).

#include <l2s/board_pose_refiner.hpp>
#include <l2s/calibrator.hpp>
#include <l2s/stereo_matcher.hpp>

#include <opencv2/core.hpp>

#include <optional>
#include <string>

namespace l2s::detail {

/// The stages run on one board hypothesis.
struct CameraAttempt {
  int candidate = -1;
  std::optional<StereoMatcher::Result> stereo;  // the region's full-resolution pass (located only)
  StereoCloud board;
  Plane plane;
  EdgeFilter::Result edges;
  CircleFinder::Result circles;
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();  // from the circles (or the markers)
  int markers = 0;  // markers found in the left image, where they gave the pose
  std::optional<BoardPoseRefiner::Result> refined;                    // default preset
};

/// The frame-wide data every hypothesis of one pair is tested against.
struct CameraFrame {
  const Image& left;
  const Image& right;
  cv::Mat left_gray, right_gray;
  const StereoCamera& cameras;
  const Target& target;
  const Calibrator::Params& params;
};

/// The board from its printed markers, the branch's first hypothesis (and
/// its only one where SGM cannot tell a printed face from its
/// surroundings): the pose their corners give in both images
/// (stereo_marker_pose.hpp), refined on the hole rims of both images
/// together with the corners (small holes' rims hold the tilt weakly, the
/// corners spread over the board hold it) where that converges (`refined`
/// is reset where it does not: the texture of a printed face draws the rim
/// search off), and kept only when no hole is seen blocked by the board's
/// own face. `why` says how, or why not.
std::optional<CameraAttempt> board_from_markers(const CameraFrame& f, std::string& why);

}  // namespace l2s::detail
