#pragma once
// The left image's edges for the calibration check (private to the library).

#include <l2s/camera.hpp>
#include <l2s/scene_observer.hpp>
#include <l2s/types.hpp>

#include <opencv2/core.hpp>

namespace l2s::detail {

/// The 8-bit gray left image in the rectified frame: as given for rectified
/// images; raw images are undistorted and rectified with K, D, R and P
/// (plumb_bob or equidistant).
cv::Mat rectified_left_gray(const Image& left, const StereoCamera& cameras);

/// Canny edges of an 8-bit gray image (255 on edges) with the observer's
/// thresholds (SceneObserver::Params: canny_low, canny_high, strong_edge)
/// adapted to it: scaled down when its strongest edges are weaker than
/// strong_edge, as a dark or flat exposure lowers every edge's step by the
/// same share, but never into its noise.
cv::Mat canny_edges(const cv::Mat& gray, const SceneObserver::Params& params);

/// Those edges and, for every pixel, the distance to the nearest edge pixel,
/// quantised as EdgeDistanceMap says.
EdgeDistanceMap edge_distance_map(const cv::Mat& gray, const SceneObserver::Params& params);

}  // namespace l2s::detail
