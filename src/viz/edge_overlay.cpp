// The calibration check's picture (overlay.hpp): lidar depth edges over the
// image edges they are scored against, so a user sees what the verdict saw.

#include <l2s/viz/overlay.hpp>

#include "check/image_edges.hpp"
#include "check/left_view.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace l2s {
namespace {

// Near is red, far is blue, as render_overlay.
cv::Scalar range_colour(double range, const OverlayParams& params) {
  static const double kStops[5][3] = {{0, 0, 255}, {0, 255, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}};
  const double t = std::clamp((range - params.min_range) / std::max(1e-9, params.max_range - params.min_range), 0.0, 1.0);
  const double s = t * 4.0;
  const int i = std::min(3, static_cast<int>(s));
  const double f = s - i;
  return cv::Scalar(kStops[i][0] * (1 - f) + kStops[i + 1][0] * f, kStops[i][1] * (1 - f) + kStops[i + 1][1] * f,
                    kStops[i][2] * (1 - f) + kStops[i + 1][2] * f);
}

void draw_points(cv::Mat& out, const detail::LidarProjector& projector, const std::vector<Eigen::Vector3d>& points,
                 int radius, const std::function<cv::Scalar(const Eigen::Vector3d&)>& colour) {
  double u, v;
  for (const auto& p : points)
    if (projector.project(p, u, v) && projector.inside(u, v))
      cv::circle(out, cv::Point(static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v))), radius, colour(p),
                 cv::FILLED, cv::LINE_8);
}

}  // namespace

Image render_edge_overlay(const Image& left, const StereoCamera& cameras, const LidarObservation& lidar,
                          const Eigen::Isometry3d& T_lidar_camera, const SceneObserver& observer,
                          const std::string& caption, const OverlayParams& params) {
  const cv::Mat gray = detail::rectified_left_gray(left, cameras);
  const cv::Mat edges = detail::canny_edges(gray, observer.params());
  cv::Mat out;
  cv::cvtColor(gray / 2, out, cv::COLOR_GRAY2BGR);
  out.setTo(cv::Scalar(255, 128, 0), edges);

  const detail::LeftView view = detail::LeftView::of(cameras);
  const detail::LidarProjector projector(view, T_lidar_camera.inverse());
  const int radius = std::clamp(params.point_radius, 0, 10);
  draw_points(out, projector, lidar.scene, 0, [&](const Eigen::Vector3d& p) { return range_colour(p.norm(), params); });
  draw_points(out, projector, lidar.scene_edges, radius, [](const Eigen::Vector3d&) { return cv::Scalar(255, 0, 255); });
  draw_points(out, projector, lidar.board_edges, radius, [](const Eigen::Vector3d&) { return cv::Scalar(0, 255, 255); });
  if (!caption.empty()) {
    const double scale = std::max(0.5, out.cols / 1600.0);
    cv::putText(out, caption, cv::Point(10, static_cast<int>(30 * scale)), cv::FONT_HERSHEY_SIMPLEX, scale,
                cv::Scalar(0, 0, 0), static_cast<int>(4 * scale), cv::LINE_AA);
    cv::putText(out, caption, cv::Point(10, static_cast<int>(30 * scale)), cv::FONT_HERSHEY_SIMPLEX, scale,
                cv::Scalar(255, 255, 255), static_cast<int>(std::max(1.0, 1.5 * scale)), cv::LINE_AA);
  }
  Image image(out.cols, out.rows, 3);
  for (int y = 0; y < out.rows; ++y) std::copy_n(out.ptr<std::uint8_t>(y), 3 * out.cols, &image.pixels[3 * y * out.cols]);
  return image;
}

}  // namespace l2s
