// The camera debug pictures of a frame inspection: the left image with what each
// stage found on it, and the disparity map.

#include <l2s/viz/inspection_images.hpp>

#include "detail/plane_frame.hpp"
#include "viz/inspection_drawing.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace l2s {
namespace {

using namespace detail;

// ---------------------------------------------------------------- camera ---

void draw_projected_polyline(cv::Mat& canvas, const CameraInfo& camera,
                             const std::vector<Eigen::Vector3d>& points, const cv::Scalar& colour,
                             int thickness) {
  std::vector<cv::Point> polygon;
  for (const auto& p : points) {
    const Eigen::Vector2d uv = camera.project(p);
    if (!uv.allFinite()) return;
    polygon.push_back(pixel(uv));
  }
  cv::polylines(canvas, polygon, true, colour, thickness, cv::LINE_AA);
}


std::string camera_counts(const CameraInspection& in) {
  char line[256];
  std::string out;
  if (in.located) out += std::to_string(in.located->cloud.size()) + " coarse stereo points";
  if (in.pass_through) out += std::to_string(in.cloud.size()) + " stereo points";
  if (in.plane) {
    std::snprintf(line, sizeof(line), " | plane: %zu candidates, %zu board-sized, %zu tried, %zu board points",
                  in.plane->candidates.size(), in.plane->ranking.size(), in.hypotheses.size(), in.board.size());
    out += line;
  }
  if (in.edges) {
    std::snprintf(line, sizeof(line),
                  " | %zu edge points (%zu on image edges, %d border lines removed)",
                  in.edges->edges.size(), in.edges->edge_points, in.edges->border_lines);
    out += line;
  }
  if (in.circles)
    out += " | " + std::to_string(in.circles->candidates.size()) + " circle candidates";
  if (in.refined)
    out += in.refined->converged ? " | rims refined" : " | rim refinement not converged";
  return out;
}

/// The image the stages worked on, in colour and dimmed, so that the drawing stands out.
cv::Mat dimmed_canvas(const Image& left) {
  cv::Mat canvas;
  Image copy = left;
  const cv::Mat view = mat_of(copy);
  if (view.channels() == 1)
    cv::cvtColor(view, canvas, cv::COLOR_GRAY2BGR);
  else
    canvas = view.clone();
  canvas *= 0.6;
  return canvas;
}

bool inside(const cv::Mat& canvas, const Eigen::Vector2i& px) {
  return px.x() >= 0 && px.y() >= 0 && px.x() < canvas.cols && px.y() < canvas.rows;
}

/// Tints the board-plane points' pixels. A mask first, so that each board
/// pixel is tinted once; a point matched at a reduced scale (or with a
/// stride) covers a block of pixels.
void tint_board(cv::Mat& canvas, const CameraInspection& in) {
  if (in.board.points.empty()) return;
  int block_w = 1, block_h = 1;
  if (in.stereo && in.stereo->disparity.scale > 0.0 && in.stereo->disparity.row_scale > 0.0) {
    block_w = std::max(1, static_cast<int>(std::lround(1.0 / in.stereo->disparity.scale)));
    block_h = std::max(1, static_cast<int>(std::lround(1.0 / in.stereo->disparity.row_scale)));
  }
  cv::Mat mask(canvas.rows, canvas.cols, CV_8UC1, cv::Scalar(0));
  for (const Eigen::Vector2i& px : in.board.pixels) {
    if (!inside(canvas, px)) continue;
    cv::rectangle(mask, cv::Rect(px.x() - block_w / 2, px.y() - block_h / 2, block_w, block_h),
                  cv::Scalar(255), cv::FILLED);
  }
  cv::Mat tinted = canvas * 0.65 + cv::Mat(canvas.size(), CV_8UC3, kBoard) * 0.35;
  tinted.copyTo(canvas, mask);
}

/// The refiner's rims (front and back face) at its final pose, even when it
/// did not converge: how far off it ended up is the diagnosis.
void draw_refiner_rims(cv::Mat& canvas, const CameraInfo& camera, const CameraInspection& in,
                       const Target& target) {
  if (!in.refined || in.refined->samples <= 0) return;
  const Eigen::Isometry3d& T = in.refined->T_camera_board;
  for (const double z : {0.0, -target.board_thickness})
    for (const auto& h : target.hole_centers())
      draw_projected_polyline(canvas, camera,
                              circle_points(T * Eigen::Vector3d(h.x(), h.y(), z), T.linear().col(2),
                                            target.hole_radius),
                              kRefined, 1);
}

/// The four labelled holes: the final centres when found; the stereo
/// circles' when a later step (the rim refinement) rejected the frame. Their
/// outlines unless the rims were refined (those are drawn already). Returns
/// the labels' places, to be drawn last, over everything.
std::vector<std::pair<int, cv::Point>> draw_holes(cv::Mat& canvas, const CameraInfo& camera,
                                                  const CameraInspection& in, const Target& target, bool refined) {
  std::vector<std::pair<int, cv::Point>> labels;
  if (!in.report.found && !(in.circles && in.circles->found)) return labels;
  HoleCenters centers = in.report.found ? in.report.centers : in.circles->centers;
  if (in.report.found && in.rectified)  // the report's centres are in the physical camera's frame
    for (Eigen::Vector3d& c : centers) c = in.rectified->R_rect_camera * c;
  const Eigen::Vector3d normal = in.T_camera_board_initial
                                     ? Eigen::Vector3d(in.T_camera_board_initial->linear().col(2))
                                     : Eigen::Vector3d(in.board_plane.normal());
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector3d& c = centers[h];
    if (!refined)
      draw_projected_polyline(canvas, camera, circle_points(c, normal, target.hole_radius), kHole, 1);
    const Eigen::Vector2d uv = camera.project(c);
    if (!uv.allFinite()) continue;
    draw_cross(canvas, pixel(uv), 8, kHole, 2);
    const Eigen::Vector2d top = camera.project(c + Eigen::Vector3d(0.0, -target.hole_radius, 0.0));
    labels.emplace_back(h, top.allFinite() ? pixel(top) + cv::Point(-12, -10) : pixel(uv));
  }
  return labels;
}

/// Numbers the circle candidates that were not matched to a hole.
void label_unmatched_candidates(cv::Mat& canvas, const CameraInfo& camera, const CircleFinder::Result& circles) {
  for (std::size_t i = 0; i < circles.candidates.size(); ++i) {
    const Circle& c = circles.candidates[i];
    const Eigen::Vector2d top = camera.project(c.center + Eigen::Vector3d(0.0, -c.radius, 0.0));
    bool matched = false;
    for (const int m : circles.matched) matched = matched || m == static_cast<int>(i);
    if (top.allFinite() && !matched)
      text(canvas, "#" + std::to_string(i), pixel(top) + cv::Point(-8, -4), kCandidate, 0.4, 1);
  }
}

}  // namespace

Image render_camera_inspection(const Image& given_left, const CameraInspection& in,
                               const StereoCamera& given_cameras, const Target& target) {
  // Raw images: draw on the rectified image the stages worked on.
  const Image& left = in.rectified ? in.rectified->left : given_left;
  const StereoCamera& cameras = in.rectified ? in.rectified->cameras : given_cameras;
  cv::Mat canvas = dimmed_canvas(left);
  const CameraInfo& camera = cameras.left;

  tint_board(canvas, in);
  if (in.circles)
    for (const Circle& c : in.circles->candidates)
      draw_projected_polyline(canvas, camera, circle_points(c.center, c.normal, c.radius), kCandidate, 1);
  draw_refiner_rims(canvas, camera, in, target);
  const bool refined = in.refined && in.refined->converged;
  const std::vector<std::pair<int, cv::Point>> labels = draw_holes(canvas, camera, in, target, refined);
  // Edge points over the circles: whether they lie on the rims is the question.
  if (in.edges)
    for (const auto& px : in.edges->edges.pixels)
      if (inside(canvas, px)) cv::circle(canvas, {px.x(), px.y()}, 1, kEdge, cv::FILLED);
  if (in.circles) label_unmatched_candidates(canvas, camera, *in.circles);
  for (const auto& [h, at] : labels) text(canvas, hole_name(static_cast<Hole>(h)), at, kHole, 0.7, 2);

  std::vector<std::pair<std::string, cv::Scalar>> items = {{"board-plane points", kBoard},
                                                           {"edge points", kEdge},
                                                           {"circle candidates", kCandidate},
                                                           {"holes (centres)", kHole}};
  if (in.refined)
    items.push_back(
        {refined ? "refined rims" : "refiner rims (not converged, not used)", kRefined});
  return image_of(stack({banner("camera", in.report, camera_counts(in), canvas.cols), canvas,
                         legend(items, canvas.cols)}));
}

Image render_disparity(const CameraInspection& inspection) {
  // The whole frame: the coarse pass when the board was located first.
  const StereoMatcher::Result* stereo = inspection.located   ? &inspection.located->stereo
                                        : inspection.stereo ? &*inspection.stereo
                                                            : nullptr;
  if (!stereo || stereo->disparity.empty()) return {};
  const DisparityMap& map = stereo->disparity;
  // Colours span the 1st..99th percentile, so that a few wild matches do not flatten the scene.
  std::vector<float> finite;
  for (const float d : map.values)
    if (std::isfinite(d)) finite.push_back(d);
  float lo = std::numeric_limits<float>::quiet_NaN(), hi = lo;
  if (!finite.empty()) {
    const auto at = [&](double q) {
      auto k = finite.begin() + static_cast<std::ptrdiff_t>(q * (finite.size() - 1));
      std::nth_element(finite.begin(), k, finite.end());
      return *k;
    };
    lo = at(0.01);
    hi = at(0.99);
  }
  cv::Mat gray(map.height, map.width, CV_8UC1, cv::Scalar(0));
  cv::Mat valid(map.height, map.width, CV_8UC1, cv::Scalar(0));
  const float span = std::max(1e-3f, hi - lo);
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      const float d = map.at(i, j);
      if (!std::isfinite(d)) continue;
      gray.at<std::uint8_t>(j, i) =
          static_cast<std::uint8_t>(std::lround(255.0f * std::clamp((d - lo) / span, 0.0f, 1.0f)));
      valid.at<std::uint8_t>(j, i) = 255;
    }
  cv::Mat colour;
  cv::applyColorMap(gray, colour, cv::COLORMAP_JET);  // large disparity (near) is red
  cv::Mat out(map.height, map.width, CV_8UC3, cv::Scalar(0, 0, 0));
  colour.copyTo(out, valid);
  if (map.row_scale > 0.0 && map.row_scale != map.scale) {  // rows matched coarser: restore the aspect
    const int rows = std::max(1, static_cast<int>(std::lround(map.height * map.scale / map.row_scale)));
    cv::resize(out, out, cv::Size(map.width, rows), 0, 0, cv::INTER_NEAREST);
  }
  if (std::isfinite(lo)) {
    char line[160];
    std::snprintf(line, sizeof(line),
                  "disparity %.1f px (blue, far) .. %.1f px (red, near), 1st..99th percentile; "
                  "black: no match",
                  lo, hi);
    text(out, line, {8, 20}, kText, 0.5, 1);
  }
  return image_of(out);
}


}  // namespace l2s
