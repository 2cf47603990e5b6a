#pragma once
// Drawing helpers shared by the debug pictures of a frame inspection
// (frame_inspector.hpp): colours with one meaning each, text with a halo,
// banners, legends. Private to the library; OpenCV stays in src/.

#include <l2s/frame_inspector.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <string>
#include <utility>
#include <vector>

namespace l2s::detail {

// BGR colours, one meaning each in both pictures.
inline const cv::Scalar kBoard(230, 160, 60);     // board-plane points (blue)
inline const cv::Scalar kEdge(0, 230, 255);       // edge points (yellow)
inline const cv::Scalar kCandidate(0, 140, 255);  // circle candidates (orange)
inline const cv::Scalar kHole(80, 220, 80);       // the four labelled holes (green)
inline const cv::Scalar kRefined(255, 255, 0);    // refined rims (cyan)
inline const cv::Scalar kRejected(60, 60, 230);   // rejected plane candidates (red)
inline const cv::Scalar kOutline(170, 170, 170);  // expected board outline (gray)
inline const cv::Scalar kText(240, 240, 240);
inline const cv::Scalar kFail(60, 60, 255);
inline const cv::Scalar kBehind(85, 85, 85);     // rays that crossed the plane before their return
inline const cv::Scalar kInFront(200, 60, 200);  // returns in front of the plane (occluders)
inline const cv::Scalar kOk(100, 230, 100);

inline cv::Mat mat_of(Image& image) {
  return cv::Mat(image.height, image.width, image.channels == 1 ? CV_8UC1 : CV_8UC3,
                 image.pixels.data());
}

inline Image image_of(const cv::Mat& mat) {
  Image image(mat.cols, mat.rows, mat.channels());
  cv::Mat view = mat_of(image);
  mat.copyTo(view);
  return image;
}

inline cv::Point pixel(const Eigen::Vector2d& p) {
  return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))};
}

inline void text(cv::Mat& canvas, const std::string& s, cv::Point at, const cv::Scalar& colour,
          double scale = 0.5, int thickness = 1) {
  // A dark halo keeps the text legible over any background.
  cv::putText(canvas, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), thickness + 2,
              cv::LINE_AA);
  cv::putText(canvas, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

// Greedy word wrap of `s` into lines at most `width` pixels wide.
inline std::vector<std::string> wrap(const std::string& s, double scale, int width) {
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
inline cv::Mat banner(const char* sensor, const BranchReport& report, const std::string& counts,
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

inline cv::Mat legend(const std::vector<std::pair<std::string, cv::Scalar>>& items, int width) {
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

inline cv::Mat stack(const std::vector<cv::Mat>& rows) {
  cv::Mat out;
  cv::vconcat(rows, out);
  return out;
}

// Points on a 3D circle, for projection or plane mapping.
inline std::vector<Eigen::Vector3d> circle_points(const Eigen::Vector3d& centre,
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

inline void draw_cross(cv::Mat& canvas, cv::Point c, int size, const cv::Scalar& colour, int thickness) {
  cv::line(canvas, {c.x - size, c.y}, {c.x + size, c.y}, colour, thickness, cv::LINE_AA);
  cv::line(canvas, {c.x, c.y - size}, {c.x, c.y + size}, colour, thickness, cv::LINE_AA);
}

}  // namespace l2s::detail
