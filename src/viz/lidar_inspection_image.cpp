// The lidar debug picture of a frame inspection: a top-down view of the sweep
// with the plane candidates, and the board plane seen face-on with the edges,
// circle candidates and labelled holes.

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

// ----------------------------------------------------------------- lidar ---

// Maps metres in a 2D view to pixels of a panel (v up = row up).
struct View {
  Eigen::Vector2d min, max;  // [m]
  double scale = 1.0;        // [px/m]
  int width = 0, height = 0;
  int margin = 30;
  cv::Point to_px(const Eigen::Vector2d& q) const {
    return {static_cast<int>(std::lround(margin + (q.x() - min.x()) * scale)),
            static_cast<int>(std::lround(height - margin - (q.y() - min.y()) * scale))};
  }
  bool inside(const Eigen::Vector2d& q) const {
    return q.x() >= min.x() && q.x() <= max.x() && q.y() >= min.y() && q.y() <= max.y();
  }
  // Fits [lo, hi] into a panel `size_px` wide, keeping the aspect ratio.
  static View fit(Eigen::Vector2d lo, Eigen::Vector2d hi, int size_px) {
    View v;
    const Eigen::Vector2d span = (hi - lo).cwiseMax(1e-3);
    v.scale = (size_px - 2.0 * v.margin) / std::max(span.x(), span.y());
    v.min = lo;
    v.max = hi;
    v.width = static_cast<int>(std::ceil(span.x() * v.scale)) + 2 * v.margin;
    v.height = static_cast<int>(std::ceil(span.y() * v.scale)) + 2 * v.margin;
    return v;
  }
};

void scale_bar(cv::Mat& panel, const View& view, double metres, const char* label) {
  const int length = static_cast<int>(std::lround(metres * view.scale));
  const cv::Point a(view.margin, panel.rows - 10), b(view.margin + length, panel.rows - 10);
  cv::line(panel, a, b, kText, 2);
  text(panel, label, {b.x + 6, b.y + 4}, kText, 0.4, 1);
}

cv::Scalar ring_colour(int ring) {
  static const cv::Scalar kPalette[6] = {{0, 230, 255},  {255, 120, 255}, {80, 255, 160},
                                         {255, 200, 80}, {120, 160, 255}, {200, 255, 255}};
  return kPalette[ring % 6];
}

// Top-down view of the filtered sweep (x forward = up, y left = left) with the
// board points and the plane candidates as lines.
cv::Mat top_down_panel(const LidarInspection& in, int size_px) {
  std::vector<double> xs, ys;
  for (const auto& p : in.cloud.points)
    if (p.allFinite()) xs.push_back(p.x()), ys.push_back(p.y());
  if (xs.size() < 3) {
    cv::Mat panel(size_px, size_px, CV_8UC3, cv::Scalar(20, 20, 20));
    text(panel, "top-down: no points after pass-through", {10, 40}, kFail);
    return panel;
  }
  const auto quantile = [](std::vector<double> v, double q) {
    const std::size_t k = static_cast<std::size_t>(q * (v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[k];
  };
  // View coordinates: (-y, x), so that forward is up and left is left.
  double lo_u = -quantile(ys, 0.99), hi_u = -quantile(ys, 0.01);
  double lo_v = quantile(xs, 0.01), hi_v = quantile(xs, 0.99);
  lo_u = std::min(lo_u, 0.0) - 0.5, hi_u = std::max(hi_u, 0.0) + 0.5;  // keep the sensor in view
  lo_v = std::min(lo_v, 0.0) - 0.5, hi_v = std::max(hi_v, 0.0) + 0.5;
  const View view = View::fit({lo_u, lo_v}, {hi_u, hi_v}, size_px);
  cv::Mat panel(std::max(view.height, size_px), view.width, CV_8UC3, cv::Scalar(20, 20, 20));
  const auto to_view = [](const Eigen::Vector3d& p) { return Eigen::Vector2d(-p.y(), p.x()); };

  for (const auto& p : in.cloud.points)
    if (p.allFinite() && view.inside(to_view(p)))
      cv::circle(panel, view.to_px(to_view(p)), 1, cv::Scalar(120, 120, 120), cv::FILLED);
  if (in.plane && in.candidate >= 0)
    for (const std::size_t i : in.plane->candidates[in.candidate].inliers)
      cv::circle(panel, view.to_px(to_view(in.cloud.points[i])), 1, kBoard, cv::FILLED);

  // Each candidate plane (near vertical) seen from above is the line n_x x + n_y y + d = 0.
  if (in.plane) {
    const auto& candidates = in.plane->candidates;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const Plane& plane = candidates[i].plane;
      const Eigen::Vector2d n(-plane.normal().y(),
                              plane.normal().x());  // normal in view coordinates
      if (n.norm() < 0.2) continue;                 // a horizontal plane has no line from above
      const Eigen::Vector2d foot = -plane.offset() * n / n.squaredNorm();
      const Eigen::Vector2d dir(-n.y(), n.x());
      const double reach = (view.max - view.min).norm();
      const cv::Scalar colour = static_cast<int>(i) == in.candidate && in.report.found ? kHole
                                : candidates[i].plausible                             ? kCandidate
                                                                                      : kRejected;
      cv::line(panel, view.to_px(foot - reach * dir.normalized()),
               view.to_px(foot + reach * dir.normalized()), colour, 1, cv::LINE_AA);
      // Label at the foot of the perpendicular from the sensor, clamped into the panel.
      cv::Point at = view.to_px(foot);
      at.x = std::clamp(at.x, 5, panel.cols - 40);
      at.y = std::clamp(at.y, 15, panel.rows - 5);
      text(panel, "P" + std::to_string(i), at, colour, 0.5, 1);
    }
  }
  const cv::Point sensor = view.to_px({0.0, 0.0});
  cv::drawMarker(panel, sensor, kText, cv::MARKER_TRIANGLE_UP, 12, 2);
  text(panel, "top-down (x forward = up)", {8, 18}, kText, 0.5, 1);
  scale_bar(panel, view, 1.0, "1 m");
  return panel;
}

// Without a board plane: why each candidate plane was rejected.
cv::Mat no_board_panel(const LidarInspection& in, int size_px) {
  cv::Mat panel(size_px, size_px, CV_8UC3, cv::Scalar(20, 20, 20));
  text(panel, "board plane: not found", {10, 40}, kFail);
  if (!in.plane) return panel;
  int y = 70;
  for (std::size_t i = 0; i < in.plane->candidates.size(); ++i) {
    const auto& c = in.plane->candidates[i];
    char head[128];
    std::snprintf(head, sizeof(head), "P%zu: %.1f deg tilt, %zu points, %.2f x %.2f m:", i,
                  std::asin(std::min(1.0, std::abs(c.plane.normal().z()))) * 180.0 / M_PI,
                  c.patch_points, c.extent_long, c.extent_short);
    text(panel, head, {10, y}, kRejected, 0.45, 1);
    y += 20;
    for (const auto& line : wrap(c.reason, 0.45, panel.cols - 40)) {
      text(panel, line, {30, y}, kText, 0.45, 1);
      y += 20;
    }
    y += 6;
  }
  return panel;
}

// Where each other point's ray crossed the board plane: behind the plane
// (seen through a hole or past the board) or in front of it (an occluder).
// Then the board points themselves.
void draw_plane_crossings(cv::Mat& panel, const View& view, const PlaneFrame& frame, const LidarInspection& in,
                          const PlaneCandidate& plane) {
  const Eigen::Vector3d n = plane.plane.normal();
  const double d = plane.plane.offset();
  std::vector<bool> on_board(in.cloud.size(), false);
  for (const std::size_t i : plane.inliers) on_board[i] = true;
  for (std::size_t i = 0; i < in.cloud.size(); ++i) {
    const Eigen::Vector3d& p = in.cloud.points[i];
    if (on_board[i] || !p.allFinite()) continue;
    const double np = n.dot(p);
    if (std::abs(np) < 1e-9) continue;
    const double s = -d / np;  // the ray s * p meets the plane
    if (s <= 0.0) continue;
    const Eigen::Vector2d q = frame.to_plane(s * p);
    if (!view.inside(q)) continue;
    cv::circle(panel, view.to_px(q), 1, s < 1.0 ? kBehind : kInFront, cv::FILLED);
  }
  for (const std::size_t i : plane.inliers) {
    const Eigen::Vector2d q = frame.to_plane(in.cloud.points[i]);
    if (view.inside(q)) cv::circle(panel, view.to_px(q), 2, kBoard, cv::FILLED);
  }
}

// The board the circles imply: outline and holes, centred and rolled as found.
void draw_implied_board(cv::Mat& panel, const View& view, const PlaneFrame& frame,
                        const CircleFinder::Result& circles, const Target& target) {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& c : circles.centers) centre += frame.to_plane(c) / 4.0;
  const double a = circles.pattern_angle;
  const Eigen::Rotation2Dd roll(a);
  std::vector<cv::Point> outline;
  for (const auto& corner : {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1),
                             Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1)})
    outline.push_back(
        view.to_px(centre + roll * Eigen::Vector2d(corner.x() * 0.5 * target.board_width,
                                                   corner.y() * 0.5 * target.board_height)));
  cv::polylines(panel, outline, true, kOutline, 1, cv::LINE_AA);
}

// The edge points, coloured by ring.
void draw_discontinuities(cv::Mat& panel, const View& view, const PlaneFrame& frame,
                          const DiscontinuityFilter::Result& discontinuities) {
  for (std::size_t i = 0; i < discontinuities.edges.size(); ++i) {
    const Eigen::Vector2d q = frame.to_plane(discontinuities.edges[i]);
    const int ring = i < discontinuities.rings.size() ? discontinuities.rings[i] : 0;
    if (view.inside(q))
      cv::circle(panel, view.to_px(q), 4, ring_colour(ring), cv::FILLED, cv::LINE_AA);
  }
}

// Every circle candidate, numbered.
void draw_circle_candidates(cv::Mat& panel, const View& view, const PlaneFrame& frame,
                            const CircleFinder::Result& circles) {
  for (std::size_t i = 0; i < circles.candidates.size(); ++i) {
    const Eigen::Vector2d q = frame.to_plane(circles.candidates[i].center);
    if (!view.inside(q)) continue;
    const int radius = static_cast<int>(std::lround(circles.candidates[i].radius * view.scale));
    cv::circle(panel, view.to_px(q), radius, kCandidate, 1, cv::LINE_AA);
    text(panel, "#" + std::to_string(i), view.to_px(q) + cv::Point(radius / 2, radius + 14),
         kCandidate, 0.4, 1);
  }
}

// The four labelled holes of the branch's report.
void draw_found_holes(cv::Mat& panel, const View& view, const PlaneFrame& frame, const BranchReport& report,
                      const Target& target) {
  for (int h = 0; h < 4; ++h) {
    const cv::Point c = view.to_px(frame.to_plane(report.centers[h]));
    const int radius = static_cast<int>(std::lround(target.hole_radius * view.scale));
    cv::circle(panel, c, radius, kHole, 2, cv::LINE_AA);
    draw_cross(panel, c, 6, kHole, 2);
    text(panel, hole_name(static_cast<Hole>(h)), c + cv::Point(-10, -radius - 6), kHole, 0.6, 2);
  }
}

// The board plane seen face-on from the sensor.
cv::Mat board_plane_panel(const LidarInspection& in, const Target& target, int size_px) {
  if (!in.plane || in.candidate < 0) return no_board_panel(in, size_px);
  const PlaneCandidate& plane = in.plane->candidates[in.candidate];
  const auto frame = detail::PlaneFrame::make(plane.plane, Eigen::Vector3d::UnitZ(),
                                              detail::centroid(in.cloud.points, plane.inliers));
  const double half_w = 0.5 * target.board_width + 0.5, half_h = 0.5 * target.board_height + 0.5;
  const View view = View::fit({-half_w, -half_h}, {half_w, half_h}, size_px);
  cv::Mat panel(std::max(view.height, size_px), view.width, CV_8UC3, cv::Scalar(20, 20, 20));

  draw_plane_crossings(panel, view, frame, in, plane);
  if (in.circles && in.circles->found) draw_implied_board(panel, view, frame, *in.circles, target);
  if (in.discontinuities) draw_discontinuities(panel, view, frame, *in.discontinuities);
  if (in.circles) draw_circle_candidates(panel, view, frame, *in.circles);
  if (in.report.found) draw_found_holes(panel, view, frame, in.report, target);
  text(panel, "in the board plane, seen from the lidar (u right, v up)", {8, 18}, kText, 0.5, 1);
  scale_bar(panel, view, 0.5, "0.5 m");
  return panel;
}

std::string lidar_counts(const LidarInspection& in) {
  char line[256];
  std::string out;
  if (in.pass_through) out += std::to_string(in.cloud.size()) + " points after pass-through";
  if (in.plane) {
    std::snprintf(line, sizeof(line), " | plane: %zu candidates, %zu board-sized, %zu tried",
                  in.plane->candidates.size(), in.plane->ranking.size(), in.hypotheses.size());
    out += line;
  }
  if (in.discontinuities) {
    const auto& c = in.discontinuities->counts;
    std::snprintf(
        line, sizeof(line),
        " | %zu edge points (%zu hole crossings, %zu strays; rings kept %zu, rejected %zu)",
        in.discontinuities->edges.size(), c.hole_crossings, c.stray_points, c.rings_kept,
        c.rings_rejected);
    out += line;
  }
  if (in.circles)
    out += " | " + std::to_string(in.circles->candidates.size()) + " circle candidates";
  return out;
}

}  // namespace

Image render_lidar_inspection(const LidarInspection& inspection, const Target& target) {
  cv::Mat left = top_down_panel(inspection, 560);
  cv::Mat right = board_plane_panel(inspection, target, 900);
  const int height = std::max(left.rows, right.rows);
  cv::copyMakeBorder(left, left, 0, height - left.rows, 0, 0, cv::BORDER_CONSTANT,
                     cv::Scalar(20, 20, 20));
  cv::copyMakeBorder(right, right, 0, height - right.rows, 0, 0, cv::BORDER_CONSTANT,
                     cv::Scalar(20, 20, 20));
  cv::Mat separator(height, 2, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::Mat panels;
  cv::hconcat(std::vector<cv::Mat>{left, separator, right}, panels);
  const cv::Mat footer = legend({{"board points", kBoard},
                                 {"other points", cv::Scalar(120, 120, 120)},
                                 {"returns behind the plane", kBehind},
                                 {"in front", kInFront},
                                 {"edges (by ring)", kEdge},
                                 {"circle candidates", kCandidate},
                                 {"holes", kHole},
                                 {"rejected planes", kRejected}},
                                panels.cols);
  return image_of(stack(
      {banner("lidar", inspection.report, lidar_counts(inspection), panels.cols), panels, footer}));
}


}  // namespace l2s
