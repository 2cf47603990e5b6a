// Edge filter of the stereo cloud (paper Sec. III-B and III-C).
// 1. Sobel: keep board-plane points whose left pixel has magnitude >= tau_sobel.
//    The magnitude is evaluated only at the points' pixels (3x3 cv::Sobel
//    kernel on the 8-bit gray image), scaled as EdgeFilter::Magnitude says.
// 2. Border lines: the outer border of the board is densely sampled and would
//    pull the circle fit, so RANSAC lines are fitted in the board plane and a
//    line is removed only when it looks like a border: close to the board's
//    horizontal or vertical, and with a contiguous run of points covering a
//    good part of the matching board side. A line tangent to hole rims only
//    gathers short chords with gaps, so rims survive.

#include <l2s/edge_filter.hpp>

#include <l2s/error.hpp>

#include "camera/cv_image.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <random>

namespace l2s {
namespace {

/// Sobel magnitude of one pixel of an 8-bit gray image, border replicated.
double sobel_magnitude(const cv::Mat& gray, int x, int y, EdgeFilter::Magnitude kind) {
  const auto px = [&](int dx, int dy) {
    const int xx = std::clamp(x + dx, 0, gray.cols - 1);
    const int yy = std::clamp(y + dy, 0, gray.rows - 1);
    return static_cast<double>(gray.at<std::uint8_t>(yy, xx));
  };
  const double gx = (px(1, -1) + 2 * px(1, 0) + px(1, 1)) - (px(-1, -1) + 2 * px(-1, 0) + px(-1, 1));
  const double gy = (px(-1, 1) + 2 * px(0, 1) + px(1, 1)) - (px(-1, -1) + 2 * px(0, -1) + px(1, -1));
  if (kind == EdgeFilter::Magnitude::HalfL1)
    return 0.5 * std::min(255.0, std::abs(gx)) + 0.5 * std::min(255.0, std::abs(gy));
  return std::min(255.0, std::hypot(gx, gy));
}

struct Line2 {
  Eigen::Vector2d point;
  Eigen::Vector2d direction;  // unit
  double distance(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d d = p - point;
    return std::abs(d.x() * direction.y() - d.y() * direction.x());
  }
};

/// Total-least-squares line through the given points.
Line2 fit_line(const std::vector<Eigen::Vector2d>& pts, const std::vector<int>& idx) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int i : idx) mean += pts[i];
  mean /= static_cast<double>(idx.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int i : idx) cov += (pts[i] - mean) * (pts[i] - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  return {mean, eig.eigenvectors().col(1).normalized()};
}

/// Longest run of sorted positions whose gaps are <= max_gap: [first, last].
std::pair<double, double> longest_run(std::vector<double> t, double max_gap) {
  std::sort(t.begin(), t.end());
  std::pair<double, double> best{t.front(), t.front()};
  double run_start = t.front();
  for (std::size_t k = 1; k <= t.size(); ++k) {
    if (k == t.size() || t[k] - t[k - 1] > max_gap) {
      if (t[k - 1] - run_start > best.second - best.first) best = {run_start, t[k - 1]};
      if (k < t.size()) run_start = t[k];
    }
  }
  return best;
}

}  // namespace

void EdgeFilter::Params::validate() const {
  if (!(sobel_threshold >= 0.0 && sobel_threshold <= 255.0))
    throw ParamError("sobel_threshold", "must be in [0, 255]");
  if (!(line_distance > 0.0)) throw ParamError("line_distance", "must be > 0");
  if (line_iterations < 1) throw ParamError("line_iterations", "must be >= 1");
  if (max_border_lines < 0 || max_border_lines > 8)
    throw ParamError("max_border_lines", "must be 0..8");
  if (min_line_points < 2) throw ParamError("min_line_points", "must be >= 2");
  if (!(max_line_tilt_deg >= 0.0 && max_line_tilt_deg <= 45.0))
    throw ParamError("max_line_tilt_deg", "must be in [0, 45]");
  if (!(min_border_fraction > 0.0 && min_border_fraction <= 1.0))
    throw ParamError("min_border_fraction", "must be in (0, 1]");
  if (!(max_gap > 0.0)) throw ParamError("max_gap", "must be > 0");
}

EdgeFilter::EdgeFilter(Params params) : params_(params) { params_.validate(); }

EdgeFilter::Result EdgeFilter::filter(const Image& left, const StereoCloud& board_cloud,
                                      const Plane& plane_camera, const Target& target) const {
  target.validate();
  if (board_cloud.pixels.size() != board_cloud.points.size())
    throw ParamError("board_cloud", "points and pixels differ in count");
  const cv::Mat gray = detail::gray_mat(left, "left");
  Result result;
  result.input_points = board_cloud.size();

  // 1. Sobel threshold at each point's pixel.
  std::vector<int> kept;
  for (std::size_t k = 0; k < board_cloud.size(); ++k) {
    const Eigen::Vector2i& px = board_cloud.pixels[k];
    if (px.x() < 0 || px.y() < 0 || px.x() >= gray.cols || px.y() >= gray.rows) continue;
    if (!board_cloud.points[k].allFinite()) continue;
    if (sobel_magnitude(gray, px.x(), px.y(), params_.magnitude) >= params_.sobel_threshold)
      kept.push_back(static_cast<int>(k));
  }
  result.edge_points = kept.size();

  // 2. Border lines in plane coordinates: "horizontal" is the camera x axis
  // projected into the plane (the board's long side is level), "vertical" its
  // in-plane perpendicular.
  std::vector<bool> removed(kept.size(), false);
  std::vector<bool> blocked(kept.size(), false);  // on a rejected line: kept, not sampled again
  const Eigen::Vector3d n = plane_camera.normal().normalized();
  Eigen::Vector3d e_h = Eigen::Vector3d::UnitX() - n * n.x();
  if (e_h.norm() < 0.1) e_h = Eigen::Vector3d::UnitY() - n * n.y();  // plane faces sideways
  e_h.normalize();
  const Eigen::Vector3d e_v = n.cross(e_h);
  std::vector<Eigen::Vector2d> uv(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const Eigen::Vector3d& p = board_cloud.points[kept[k]];
    uv[k] = {p.dot(e_h), p.dot(e_v)};
  }
  std::mt19937_64 rng(params_.seed);
  const double cos_tilt = std::cos(params_.max_line_tilt_deg * M_PI / 180.0);
  // A rejected candidate (hole tangent, short piece) blocks its points and the
  // search goes on, so a border with fewer points than it is still found.
  const int max_attempts = 3 * params_.max_border_lines;
  for (int attempt = 0; params_.remove_border_lines && attempt < max_attempts &&
                        result.border_lines < params_.max_border_lines;
       ++attempt) {
    std::vector<int> alive;
    for (std::size_t k = 0; k < kept.size(); ++k)
      if (!removed[k] && !blocked[k]) alive.push_back(static_cast<int>(k));
    if (static_cast<int>(alive.size()) < params_.min_line_points) break;
    std::uniform_int_distribution<std::size_t> pick(0, alive.size() - 1);
    std::vector<int> best_inliers;
    for (int it = 0; it < params_.line_iterations; ++it) {
      const Eigen::Vector2d& a = uv[alive[pick(rng)]];
      const Eigen::Vector2d& b = uv[alive[pick(rng)]];
      if ((b - a).norm() < 1e-6) continue;
      const Eigen::Vector2d dir = (b - a).normalized();
      // Only candidate borders are worth counting: orientation first.
      if (std::max(std::abs(dir.x()), std::abs(dir.y())) < cos_tilt) continue;
      const Line2 candidate{a, dir};
      std::vector<int> inliers;
      for (int k : alive)
        if (candidate.distance(uv[k]) <= params_.line_distance) inliers.push_back(k);
      if (inliers.size() > best_inliers.size()) best_inliers.swap(inliers);
    }
    if (static_cast<int>(best_inliers.size()) < params_.min_line_points) break;
    const Line2 fitted = fit_line(uv, best_inliers);
    const bool horizontal = std::abs(fitted.direction.x()) >= std::abs(fitted.direction.y());
    const bool level = std::max(std::abs(fitted.direction.x()), std::abs(fitted.direction.y())) >= cos_tilt;
    std::vector<int> on_line;
    std::vector<double> t;
    for (int k : alive)
      if (fitted.distance(uv[k]) <= params_.line_distance) {
        on_line.push_back(k);
        t.push_back((uv[k] - fitted.point).dot(fitted.direction));
      }
    if (on_line.empty()) break;
    const auto [t0, t1] = longest_run(t, params_.max_gap);
    const double side = horizontal ? target.board_width : target.board_height;
    if (!level || t1 - t0 < params_.min_border_fraction * side) {
      for (int k : best_inliers) blocked[k] = true;
      continue;
    }
    for (std::size_t m = 0; m < on_line.size(); ++m)
      if (t[m] >= t0 - params_.max_gap && t[m] <= t1 + params_.max_gap) {
        removed[on_line[m]] = true;
        ++result.border_points;
      }
    ++result.border_lines;
  }

  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (removed[k]) continue;
    result.edges.points.push_back(board_cloud.points[kept[k]]);
    result.edges.pixels.push_back(board_cloud.pixels[kept[k]]);
  }
  result.found = !result.edges.points.empty();
  if (!result.found)
    result.reason = result.edge_points == 0 ? "no board point lies on an image edge"
                                            : "only border-line points were on edges";
  return result;
}

}  // namespace l2s
