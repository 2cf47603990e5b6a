// Debug pictures of a frame inspection (frame_inspector.hpp): what each stage
// of a branch saw, drawn so that "why is the board not found" is answered by
// looking. OpenCV draws; nothing of it leaves this file.

#include <l2s/frame_inspector.hpp>

#include "detail/plane_frame.hpp"

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

constexpr const char* kHoleLabels[4] = {"TL", "TR", "BL", "BR"};

// BGR colours, one meaning each in both pictures.
const cv::Scalar kBoard(230, 160, 60);     // board-plane points (blue)
const cv::Scalar kEdge(0, 230, 255);       // edge points (yellow)
const cv::Scalar kCandidate(0, 140, 255);  // circle candidates (orange)
const cv::Scalar kHole(80, 220, 80);       // the four labelled holes (green)
const cv::Scalar kRefined(255, 255, 0);    // refined rims (cyan)
const cv::Scalar kRejected(60, 60, 230);   // rejected plane candidates (red)
const cv::Scalar kOutline(170, 170, 170);  // expected board outline (gray)
const cv::Scalar kText(240, 240, 240);
const cv::Scalar kFail(60, 60, 255);
const cv::Scalar kBehind(85, 85, 85);     // rays that crossed the plane before their return
const cv::Scalar kInFront(200, 60, 200);  // returns in front of the plane (occluders)
const cv::Scalar kOk(100, 230, 100);

cv::Mat mat_of(Image& image) {
  return cv::Mat(image.height, image.width, image.channels == 1 ? CV_8UC1 : CV_8UC3,
                 image.pixels.data());
}

Image image_of(const cv::Mat& mat) {
  Image image(mat.cols, mat.rows, mat.channels());
  cv::Mat view = mat_of(image);
  mat.copyTo(view);
  return image;
}

cv::Point pixel(const Eigen::Vector2d& p) {
  return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))};
}

void text(cv::Mat& canvas, const std::string& s, cv::Point at, const cv::Scalar& colour,
          double scale = 0.5, int thickness = 1) {
  // A dark halo keeps the text legible over any background.
  cv::putText(canvas, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), thickness + 2,
              cv::LINE_AA);
  cv::putText(canvas, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

// Greedy word wrap of `s` into lines at most `width` pixels wide.
std::vector<std::string> wrap(const std::string& s, double scale, int width) {
  std::vector<std::string> lines;
  std::string line, word;
  const auto fits = [&](const std::string& candidate) {
    int baseline = 0;
    return cv::getTextSize(candidate, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline).width <= width;
  };
  std::size_t start = 0;
  while (start < s.size()) {
    std::size_t end = s.find(' ', start);
    if (end == std::string::npos) end = s.size();
    word = s.substr(start, end - start);
    start = end + 1;
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (line.empty() || fits(candidate)) {
      line = candidate;
    } else {
      lines.push_back(line);
      line = word;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// Status banner: found, or the failing stage and its reason (wrapped), then
// one line of counts so that the picture speaks without the text report.
cv::Mat banner(const char* sensor, const BranchReport& report, const std::string& counts,
               int width) {
  const std::string status = report.found ? std::string(sensor) + ": FOUND four labelled holes"
                                          : std::string(sensor) + ": FAILED at " +
                                                report.failed_stage + ": " + report.reason;
  std::vector<std::string> lines = wrap(status, 0.5, width - 16);
  if (!report.note.empty())
    for (const auto& line : wrap("note: " + report.note, 0.5, width - 16)) lines.push_back(line);
  const std::size_t status_lines = lines.size();
  for (const auto& line : wrap(counts, 0.45, width - 16)) lines.push_back(line);
  cv::Mat band(static_cast<int>(8 + 20 * lines.size()), width, CV_8UC3, cv::Scalar(30, 30, 30));
  for (std::size_t i = 0; i < lines.size(); ++i)
    text(band, lines[i], {8, static_cast<int>(20 + 20 * i)},
         i >= status_lines ? kText : (report.found ? kOk : kFail), i >= status_lines ? 0.45 : 0.5,
         1);
  return band;
}

cv::Mat legend(const std::vector<std::pair<std::string, cv::Scalar>>& items, int width) {
  cv::Mat band(24, width, CV_8UC3, cv::Scalar(30, 30, 30));
  int x = 8;
  for (const auto& [name, colour] : items) {
    cv::circle(band, {x + 5, 12}, 5, colour, cv::FILLED, cv::LINE_AA);
    text(band, name, {x + 14, 17}, kText, 0.45, 1);
    int baseline = 0;
    x += 30 + cv::getTextSize(name, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &baseline).width;
  }
  return band;
}

cv::Mat stack(const std::vector<cv::Mat>& rows) {
  cv::Mat out;
  cv::vconcat(rows, out);
  return out;
}

// Points on a 3D circle, for projection or plane mapping.
std::vector<Eigen::Vector3d> circle_points(const Eigen::Vector3d& centre,
                                           const Eigen::Vector3d& normal, double radius,
                                           int count = 96) {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d a = n.unitOrthogonal();
  const Eigen::Vector3d b = n.cross(a);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const double t = 2.0 * M_PI * i / count;
    points.push_back(centre + radius * (std::cos(t) * a + std::sin(t) * b));
  }
  return points;
}

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

void draw_cross(cv::Mat& canvas, cv::Point c, int size, const cv::Scalar& colour, int thickness) {
  cv::line(canvas, {c.x - size, c.y}, {c.x + size, c.y}, colour, thickness, cv::LINE_AA);
  cv::line(canvas, {c.x, c.y - size}, {c.x, c.y + size}, colour, thickness, cv::LINE_AA);
}

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
  if (in.plane)
    for (const std::size_t i : in.plane->inliers)
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
      const cv::Scalar colour = candidates[i].accepted ? kHole : kRejected;
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

// The board plane seen face-on from the sensor.
cv::Mat board_plane_panel(const LidarInspection& in, const Target& target, int size_px) {
  if (!in.plane || !in.plane->found) {
    cv::Mat panel(size_px, size_px, CV_8UC3, cv::Scalar(20, 20, 20));
    text(panel, "board plane: not found", {10, 40}, kFail);
    if (in.plane) {
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
    }
    return panel;
  }
  const auto& plane = *in.plane;
  const auto frame = detail::PlaneFrame::make(plane.plane, Eigen::Vector3d::UnitZ(),
                                              detail::centroid(in.cloud.points, plane.inliers));
  const double half_w = 0.5 * target.board_width + 0.5, half_h = 0.5 * target.board_height + 0.5;
  const View view = View::fit({-half_w, -half_h}, {half_w, half_h}, size_px);
  cv::Mat panel(std::max(view.height, size_px), view.width, CV_8UC3, cv::Scalar(20, 20, 20));

  // Where each other point's ray crossed the board plane: behind the plane
  // (seen through a hole or past the board) or in front of it (an occluder).
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

  // The board the circles imply: outline and holes, centred and rolled as found.
  if (in.circles && in.circles->found) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& c : in.circles->centers) centre += frame.to_plane(c) / 4.0;
    const double a = in.circles->pattern_angle;
    const Eigen::Rotation2Dd roll(a);
    std::vector<cv::Point> outline;
    for (const auto& corner : {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1),
                               Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1)})
      outline.push_back(
          view.to_px(centre + roll * Eigen::Vector2d(corner.x() * 0.5 * target.board_width,
                                                     corner.y() * 0.5 * target.board_height)));
    cv::polylines(panel, outline, true, kOutline, 1, cv::LINE_AA);
  }

  if (in.discontinuities)
    for (std::size_t i = 0; i < in.discontinuities->edges.size(); ++i) {
      const Eigen::Vector2d q = frame.to_plane(in.discontinuities->edges[i]);
      const int ring = i < in.discontinuities->rings.size() ? in.discontinuities->rings[i] : 0;
      if (view.inside(q))
        cv::circle(panel, view.to_px(q), 4, ring_colour(ring), cv::FILLED, cv::LINE_AA);
    }

  if (in.circles) {
    const auto& r = *in.circles;
    for (std::size_t i = 0; i < r.candidates.size(); ++i) {
      const Eigen::Vector2d q = frame.to_plane(r.candidates[i].center);
      if (!view.inside(q)) continue;
      const int radius = static_cast<int>(std::lround(r.candidates[i].radius * view.scale));
      cv::circle(panel, view.to_px(q), radius, kCandidate, 1, cv::LINE_AA);
      text(panel, "#" + std::to_string(i), view.to_px(q) + cv::Point(radius / 2, radius + 14),
           kCandidate, 0.4, 1);
    }
  }
  if (in.report.found)
    for (int h = 0; h < 4; ++h) {
      const cv::Point c = view.to_px(frame.to_plane(in.report.centers[h]));
      const int radius = static_cast<int>(std::lround(target.hole_radius * view.scale));
      cv::circle(panel, c, radius, kHole, 2, cv::LINE_AA);
      draw_cross(panel, c, 6, kHole, 2);
      text(panel, kHoleLabels[h], c + cv::Point(-10, -radius - 6), kHole, 0.6, 2);
    }
  text(panel, "in the board plane, seen from the lidar (u right, v up)", {8, 18}, kText, 0.5, 1);
  scale_bar(panel, view, 0.5, "0.5 m");
  return panel;
}

std::string lidar_counts(const LidarInspection& in) {
  char line[256];
  std::string out;
  if (in.pass_through) out += std::to_string(in.cloud.size()) + " points after pass-through";
  if (in.plane) {
    std::snprintf(line, sizeof(line), " | plane: %zu candidates, %zu board points",
                  in.plane->candidates.size(), in.plane->inliers.size());
    out += line;
  }
  if (in.discontinuities) {
    const auto& c = in.discontinuities->counts;
    std::snprintf(
        line, sizeof(line),
        " | %zu edge points (%zu discontinuities, %zu border; rings kept %zu, rejected %zu)",
        in.discontinuities->edges.size(), c.discontinuities, c.border_points, c.rings_kept,
        c.rings_rejected);
    out += line;
  }
  if (in.circles)
    out += " | " + std::to_string(in.circles->candidates.size()) + " circle candidates";
  return out;
}

std::string camera_counts(const CameraInspection& in) {
  char line[256];
  std::string out;
  if (in.stereo) out += std::to_string(in.stereo->cloud.size()) + " stereo points";
  if (in.pass_through) out += ", " + std::to_string(in.cloud.size()) + " after pass-through";
  if (in.plane) {
    std::snprintf(line, sizeof(line), " | plane: %zu candidates, %zu board points",
                  in.plane->candidates.size(), in.plane->inliers.size());
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

Image render_camera_inspection(const Image& left, const CameraInspection& in,
                               const StereoCamera& cameras, const Target& target) {
  cv::Mat canvas;
  {
    Image copy = left;
    const cv::Mat view = mat_of(copy);
    if (view.channels() == 1)
      cv::cvtColor(view, canvas, cv::COLOR_GRAY2BGR);
    else
      canvas = view.clone();
  }
  canvas *= 0.6;  // dimmed, so that the drawing stands out
  const CameraInfo& camera = cameras.left;
  const auto inside = [&](const Eigen::Vector2i& px) {
    return px.x() >= 0 && px.y() >= 0 && px.x() < canvas.cols && px.y() < canvas.rows;
  };

  if (in.plane) {
    // A mask first, so that each board pixel is tinted once; a point matched at
    // a reduced scale (or with a stride) covers a block of pixels.
    int block = 1;
    if (in.stereo && in.stereo->disparity.scale > 0.0)
      block = std::max(1, static_cast<int>(std::lround(1.0 / in.stereo->disparity.scale)));
    cv::Mat mask(canvas.rows, canvas.cols, CV_8UC1, cv::Scalar(0));
    for (const std::size_t i : in.plane->inliers) {
      const Eigen::Vector2i& px = in.cloud.pixels[i];
      if (!inside(px)) continue;
      cv::rectangle(mask, cv::Rect(px.x() - block / 2, px.y() - block / 2, block, block),
                    cv::Scalar(255), cv::FILLED);
    }
    cv::Mat tinted = canvas * 0.65 + cv::Mat(canvas.size(), CV_8UC3, kBoard) * 0.35;
    tinted.copyTo(canvas, mask);
  }

  if (in.circles) {
    const auto& r = *in.circles;
    for (std::size_t i = 0; i < r.candidates.size(); ++i) {
      const Circle& c = r.candidates[i];
      draw_projected_polyline(canvas, camera, circle_points(c.center, c.normal, c.radius),
                              kCandidate, 1);
    }
  }
  // The refiner's rims (front and back face) at its final pose, even when it
  // did not converge: how far off it ended up is the diagnosis.
  if (in.refined && in.refined->samples > 0) {
    const Eigen::Isometry3d& T = in.refined->T_camera_board;
    for (const double z : {0.0, -target.board_thickness})
      for (const auto& h : target.hole_centers())
        draw_projected_polyline(canvas, camera,
                                circle_points(T * Eigen::Vector3d(h.x(), h.y(), z),
                                              T.linear().col(2), target.hole_radius),
                                kRefined, 1);
  }
  const bool refined = in.refined && in.refined->converged;
  std::vector<std::pair<int, cv::Point>> labels;  // drawn last, over everything
  // The four labelled holes: the final centres when found; the stereo circles'
  // when a later step (the rim refinement) rejected the frame.
  if (in.report.found || (in.circles && in.circles->found)) {
    const HoleCenters& centers = in.report.found ? in.report.centers : in.circles->centers;
    const Eigen::Vector3d normal = in.T_camera_board_initial
                                       ? Eigen::Vector3d(in.T_camera_board_initial->linear().col(2))
                                       : Eigen::Vector3d(in.plane->plane.normal());
    for (int h = 0; h < 4; ++h) {
      const Eigen::Vector3d& c = centers[h];
      if (!refined)
        draw_projected_polyline(canvas, camera, circle_points(c, normal, target.hole_radius), kHole,
                                1);
      const Eigen::Vector2d uv = camera.project(c);
      if (!uv.allFinite()) continue;
      draw_cross(canvas, pixel(uv), 8, kHole, 2);
      const Eigen::Vector2d top =
          camera.project(c + Eigen::Vector3d(0.0, -target.hole_radius, 0.0));
      labels.emplace_back(h, top.allFinite() ? pixel(top) + cv::Point(-12, -10) : pixel(uv));
    }
  }
  // Edge points over the circles: whether they lie on the rims is the question.
  if (in.edges)
    for (const auto& px : in.edges->edges.pixels)
      if (inside(px)) cv::circle(canvas, {px.x(), px.y()}, 1, kEdge, cv::FILLED);
  if (in.circles)
    for (std::size_t i = 0; i < in.circles->candidates.size(); ++i) {
      const Circle& c = in.circles->candidates[i];
      const Eigen::Vector2d top = camera.project(c.center + Eigen::Vector3d(0.0, -c.radius, 0.0));
      bool matched = false;
      for (const int m : in.circles->matched) matched = matched || m == static_cast<int>(i);
      if (top.allFinite() && !matched)
        text(canvas, "#" + std::to_string(i), pixel(top) + cv::Point(-8, -4), kCandidate, 0.4, 1);
    }
  for (const auto& [h, at] : labels) text(canvas, kHoleLabels[h], at, kHole, 0.7, 2);

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
  if (!inspection.stereo || inspection.stereo->disparity.empty()) return {};
  const DisparityMap& map = inspection.stereo->disparity;
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
