#pragma once
// The target's ArUco markers in one image (the pose they give: marker_pose.hpp).

#include <l2s/mono_board_detector.hpp>

#include <opencv2/core.hpp>

#include <array>
#include <optional>
#include <vector>

namespace l2s::detail {

/// The markers of `layout` found in `gray` (cv::aruco, sub-pixel corners),
/// in the order of layout.ids; ids not in the layout are dropped, and an id
/// found twice is dropped altogether (which one is the board's is unknown).
std::vector<MonoBoardDetector::Marker> find_target_markers(const cv::Mat& gray, const MarkerLayout& layout);

/// Where `marker`'s four corners lie on the board (board frame, ArUco
/// order), or nothing when its id is not one of `layout`'s.
std::optional<std::array<Eigen::Vector3d, 4>> board_corners(const MonoBoardDetector::Marker& marker,
                                                            const MarkerLayout& layout);

/// The corners of the markers of `layout` among `markers`, as points the
/// rim refinement fits together with the rims (board frame and pixel).
std::vector<BoardPoseRefiner::PointObservation> corner_observations(const std::vector<MonoBoardDetector::Marker>& markers,
                                                                    const MarkerLayout& layout);

}  // namespace l2s::detail
