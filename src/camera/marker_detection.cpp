// Marker detection with OpenCV's aruco module (Garrido-Jurado et al. 2014).

#include "camera/marker_detection.hpp"

#include "detail/aruco_dictionary.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {

std::vector<MonoBoardDetector::Marker> find_target_markers(const cv::Mat& gray, const MarkerLayout& layout) {
  const cv::Ptr<cv::aruco::Dictionary> dictionary = aruco_dictionary(layout.dictionary);
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  // Sub-pixel corners: the pose, and so the hole centres, rest on them.
  params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  params->cornerRefinementWinSize = 4;
  params->cornerRefinementMaxIterations = 50;
  params->cornerRefinementMinAccuracy = 0.005;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(gray, dictionary, corners, ids, params);

  std::vector<MonoBoardDetector::Marker> found;
  for (int wanted : layout.ids) {
    if (std::count(ids.begin(), ids.end(), wanted) != 1) continue;
    const std::size_t k = static_cast<std::size_t>(std::find(ids.begin(), ids.end(), wanted) - ids.begin());
    MonoBoardDetector::Marker marker;
    marker.id = wanted;
    for (std::size_t c = 0; c < 4; ++c) marker.corners_px[c] = Eigen::Vector2d(corners[k][c].x, corners[k][c].y);
    found.push_back(marker);
  }
  return found;
}

std::optional<std::array<Eigen::Vector3d, 4>> board_corners(const MonoBoardDetector::Marker& marker,
                                                            const MarkerLayout& layout) {
  const auto found = std::find(layout.ids.begin(), layout.ids.end(), marker.id);
  if (found == layout.ids.end()) return std::nullopt;
  return layout.corners(static_cast<std::size_t>(found - layout.ids.begin()));
}

std::vector<BoardPoseRefiner::PointObservation> corner_observations(const std::vector<MonoBoardDetector::Marker>& markers,
                                                                    const MarkerLayout& layout) {
  std::vector<BoardPoseRefiner::PointObservation> points;
  for (const auto& marker : markers)
    if (const auto corners = board_corners(marker, layout))
      for (std::size_t c = 0; c < 4; ++c) points.push_back({(*corners)[c], marker.corners_px[c]});
  return points;
}

}  // namespace l2s::detail
