// Edge filter of the stereo board (paper Sec. III-B and III-C).
// 1. Sobel: the paper keeps board-plane stereo points whose left pixel has
//    magnitude >= tau_sobel. Stereo is weakest exactly at the rims (matching
//    windows straddle them), so here the left image's own edge pixels inside
//    the board's region (its points' pixels, widened) are cast onto the board
//    plane instead. tau_sobel drops to a quantile of the region's magnitudes
//    when the board shows little contrast (another camera's exposure, a board
//    close in brightness to its background).
// 2. Border lines: the outer border of the board is densely sampled and would
//    pull the circle fit, so RANSAC lines are fitted in the board plane and a
//    line is removed only when it looks like a border: close to the board's
//    horizontal or vertical, and with a contiguous run of points covering a
//    good part of the matching board side. A line tangent to hole rims only
//    gathers short chords with gaps, so rims survive.

#include <l2s/edge_filter.hpp>

#include <l2s/error.hpp>

#include "camera/cv_image.hpp"
#include "camera/noise_level.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <random>

namespace l2s {
namespace {

/// Sobel responses of a gray crop and their magnitude, scaled to 0..255 as EdgeFilter::Magnitude says.
struct Sobel {
  cv::Mat gx, gy, magnitude;
};

Sobel sobel_of_channel(const cv::Mat& gray, EdgeFilter::Magnitude kind) {
  Sobel out;
  cv::Mat& gx = out.gx;
  cv::Mat& gy = out.gy;
  cv::Mat& magnitude = out.magnitude;
  cv::Sobel(gray, gx, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(gray, gy, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  if (kind == EdgeFilter::Magnitude::HalfL1) {
    cv::Mat ax = cv::min(cv::abs(gx), 255.0f), ay = cv::min(cv::abs(gy), 255.0f);
    magnitude = 0.5f * ax + 0.5f * ay;
  } else {
    cv::magnitude(gx, gy, magnitude);
    magnitude = cv::min(magnitude, 255.0f);
  }
  return out;
}

/// As above for a gray or colour crop: in colour, each pixel takes the
/// channel with the strongest response.
Sobel sobel_of(const cv::Mat& image, EdgeFilter::Magnitude kind) {
  if (image.channels() == 1) return sobel_of_channel(image, kind);
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  Sobel out = sobel_of_channel(channels[0], kind);
  for (std::size_t c = 1; c < channels.size(); ++c) {
    const Sobel other = sobel_of_channel(channels[c], kind);
    const cv::Mat stronger = other.magnitude > out.magnitude;
    other.gx.copyTo(out.gx, stronger);
    other.gy.copyTo(out.gy, stronger);
    other.magnitude.copyTo(out.magnitude, stronger);
  }
  return out;
}

/// Where pixel (x, y) looks on the plane, or nothing when the ray misses it.
bool cast_onto(const CameraInfo& camera, const Plane& plane, double x, double y, Eigen::Vector3d& out) {
  const Eigen::Vector3d ray((x - camera.cx()) / camera.fx(), (y - camera.cy()) / camera.fy(), 1.0);
  const double denom = plane.normal().dot(ray);
  if (std::abs(denom) < 1e-9) return false;
  const double t = -plane.offset() / denom;
  if (t <= 0.0) return false;
  out = t * ray;
  return true;
}

struct EdgePixels {
  std::vector<Eigen::Vector3d> points;     // on the plane, camera frame
  std::vector<Eigen::Vector3d> gradients;  // unit, in the plane: where the image gradient points
  std::vector<Eigen::Vector2i> pixels;
  double threshold = 0.0;
};

/// The image edges of the board's region, cast onto the board plane. The
/// region is where board points are, widened by a few pixels: stereo gives
/// no points right at a rim (matching windows straddle it), the image does.
/// The threshold is the paper's tau_sobel, lowered to a fraction of the
/// region's strong edges (a high quantile: rims and outline are a few % of the
/// region) when the board shows little contrast.
EdgePixels edge_pixels(const cv::Mat& image, const CameraInfo& camera, const StereoCloud& board,
                       const Plane& plane, const EdgeFilter::Params& params) {
  EdgePixels out;
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
  for (const Eigen::Vector2i& px : board.pixels)
    if (px.x() >= 0 && px.y() >= 0 && px.x() < image.cols && px.y() < image.rows) mask.at<std::uint8_t>(px.y(), px.x()) = 255;
  const int k = params.region_dilation_px;
  cv::dilate(mask, mask, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * k + 1, 2 * k + 1)));
  const cv::Rect box = cv::boundingRect(mask);
  if (box.area() <= 0) return out;
  const cv::Rect padded = (box + cv::Size(2, 2) - cv::Point(1, 1)) & cv::Rect(0, 0, image.cols, image.rows);
  const Sobel sobel = sobel_of(image(padded), params.magnitude);
  const cv::Mat& magnitude = sobel.magnitude;
  std::vector<float> values;
  for (int y = box.y; y < box.y + box.height; ++y)
    for (int x = box.x; x < box.x + box.width; ++x)
      if (mask.at<std::uint8_t>(y, x)) values.push_back(magnitude.at<float>(y - padded.y, x - padded.x));
  if (values.empty()) return out;
  out.threshold = params.sobel_threshold;
  // A Sobel response has 3.5 times the image noise's sigma per axis; four of
  // those keep noise out of the edges of a low-contrast board.
  const double noise_floor = params.noise_factor * std::sqrt(12.0) * detail::image_noise_sigma(image);
  if (params.adaptive_quantile > 0.0) {
    auto q = values.begin() + static_cast<std::ptrdiff_t>(params.adaptive_quantile * (values.size() - 1));
    std::nth_element(values.begin(), q, values.end());
    const double adaptive = params.adaptive_fraction * static_cast<double>(*q);
    out.threshold =
        std::min(params.sobel_threshold, std::max({params.min_sobel_threshold, noise_floor, adaptive}));
  }
  for (int y = box.y; y < box.y + box.height; ++y)
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (!mask.at<std::uint8_t>(y, x) || magnitude.at<float>(y - padded.y, x - padded.x) < out.threshold) continue;
      // The gradient's direction on the plane: where a step along it in the image lands.
      Eigen::Vector2d g(sobel.gx.at<float>(y - padded.y, x - padded.x), sobel.gy.at<float>(y - padded.y, x - padded.x));
      g.normalize();
      Eigen::Vector3d p, step;
      if (!cast_onto(camera, plane, x, y, p) || !cast_onto(camera, plane, x + g.x(), y + g.y(), step)) continue;
      out.points.push_back(p);
      out.gradients.push_back((step - p).normalized());
      out.pixels.emplace_back(x, y);
    }
  return out;
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

/// Board-plane coordinates of the points: "horizontal" is the camera x axis
/// projected into the plane (the board's long side is level), "vertical" its
/// in-plane perpendicular.
std::vector<Eigen::Vector2d> board_plane_uv(const std::vector<Eigen::Vector3d>& points, const Plane& plane) {
  const Eigen::Vector3d n = plane.normal().normalized();
  Eigen::Vector3d e_h = Eigen::Vector3d::UnitX() - n * n.x();
  if (e_h.norm() < 0.1) e_h = Eigen::Vector3d::UnitY() - n * n.y();  // plane faces sideways
  e_h.normalize();
  const Eigen::Vector3d e_v = n.cross(e_h);
  std::vector<Eigen::Vector2d> uv(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) uv[k] = {points[k].dot(e_h), points[k].dot(e_v)};
  return uv;
}

/// RANSAC over the `alive` points for the line with most inliers among those
/// within the tilt of the board's horizontal or vertical; its inliers.
std::vector<int> most_supported_line(const std::vector<Eigen::Vector2d>& uv, const std::vector<int>& alive,
                                     const EdgeFilter::Params& params, double cos_tilt, std::mt19937_64& rng) {
  std::uniform_int_distribution<std::size_t> pick(0, alive.size() - 1);
  std::vector<int> best_inliers;
  for (int it = 0; it < params.line_iterations; ++it) {
    const Eigen::Vector2d& a = uv[alive[pick(rng)]];
    const Eigen::Vector2d& b = uv[alive[pick(rng)]];
    if ((b - a).norm() < 1e-6) continue;
    const Eigen::Vector2d dir = (b - a).normalized();
    // Only candidate borders are worth counting: orientation first.
    if (std::max(std::abs(dir.x()), std::abs(dir.y())) < cos_tilt) continue;
    // Counted first: most samples lose and need no list of their inliers.
    const Line2 candidate{a, dir};
    std::size_t count = 0;
    for (int k : alive) count += candidate.distance(uv[k]) <= params.line_distance;
    if (count <= best_inliers.size()) continue;
    best_inliers.clear();
    for (int k : alive)
      if (candidate.distance(uv[k]) <= params.line_distance) best_inliers.push_back(k);
  }
  return best_inliers;
}

/// Whether the board lies on one side of the line only, along its run
/// [t0, t1]: board points in a band beside it (beyond the stereo's fattening
/// of the border) are counted on each side. A long level line inside the
/// board (wood grain, a printed stripe) has board on both sides; removing it
/// as a border would spend the budget of border lines and leave the real
/// border to pull the circles.
bool board_on_one_side(const Line2& line, double t0, double t1, const std::vector<Eigen::Vector2d>& board_uv) {
  constexpr double kNear = 0.03, kFar = 0.08;  // [m] the band beside the line
  constexpr double kOuterShare = 0.25;         // the outer side holds at most this share of the inner's points
  int left = 0, right = 0;
  const Eigen::Vector2d normal(-line.direction.y(), line.direction.x());
  for (const Eigen::Vector2d& p : board_uv) {
    const Eigen::Vector2d d = p - line.point;
    const double t = d.dot(line.direction), n = d.dot(normal);
    if (t < t0 || t > t1 || std::abs(n) < kNear || std::abs(n) > kFar) continue;
    ++(n > 0.0 ? left : right);
  }
  return std::min(left, right) <= kOuterShare * std::max(left, right);
}

/// Which points lie on the board's border lines (step 2 of the file
/// comment); counts them and the lines in `result`. A rejected candidate
/// (hole tangent, short piece, a line with board on both sides) blocks its
/// points and the search goes on, so a border with fewer points than it is
/// still found.
std::vector<bool> border_line_points(const std::vector<Eigen::Vector2d>& uv, const std::vector<Eigen::Vector2d>& board_uv,
                                     const Target& target, const EdgeFilter::Params& params,
                                     EdgeFilter::Result& result) {
  std::vector<bool> removed(uv.size(), false);
  std::vector<bool> blocked(uv.size(), false);  // on a rejected line: kept, not sampled again
  std::mt19937_64 rng(params.seed);
  const double cos_tilt = std::cos(params.max_line_tilt_deg * M_PI / 180.0);
  // Lines inside the board (grain, stripes) are tried and blocked before the
  // borders they outnumber; a wood-grain board has dozens.
  const int max_attempts = 12 * params.max_border_lines;
  for (int attempt = 0; params.remove_border_lines && attempt < max_attempts &&
                        result.border_lines < params.max_border_lines;
       ++attempt) {
    std::vector<int> alive;
    for (std::size_t k = 0; k < uv.size(); ++k)
      if (!removed[k] && !blocked[k]) alive.push_back(static_cast<int>(k));
    if (static_cast<int>(alive.size()) < params.min_line_points) break;
    const std::vector<int> best_inliers = most_supported_line(uv, alive, params, cos_tilt, rng);
    if (static_cast<int>(best_inliers.size()) < params.min_line_points) break;
    const Line2 fitted = fit_line(uv, best_inliers);
    const bool horizontal = std::abs(fitted.direction.x()) >= std::abs(fitted.direction.y());
    const bool level = std::max(std::abs(fitted.direction.x()), std::abs(fitted.direction.y())) >= cos_tilt;
    std::vector<int> on_line;
    std::vector<double> t;
    for (int k : alive)
      if (fitted.distance(uv[k]) <= params.line_distance) {
        on_line.push_back(k);
        t.push_back((uv[k] - fitted.point).dot(fitted.direction));
      }
    if (on_line.empty()) break;
    const auto [t0, t1] = longest_run(t, params.max_gap);
    const double side = horizontal ? target.board_width : target.board_height;
    if (!level || t1 - t0 < params.min_border_fraction * side || !board_on_one_side(fitted, t0, t1, board_uv)) {
      for (int k : best_inliers) blocked[k] = true;
      continue;
    }
    for (std::size_t m = 0; m < on_line.size(); ++m)
      if (t[m] >= t0 - params.max_gap && t[m] <= t1 + params.max_gap) {
        removed[on_line[m]] = true;
        ++result.border_points;
      }
    ++result.border_lines;
  }
  return removed;
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
  if (!(adaptive_quantile >= 0.0 && adaptive_quantile <= 1.0))
    throw ParamError("adaptive_quantile", "must be in [0, 1]");
  if (!(adaptive_fraction > 0.0 && adaptive_fraction <= 1.0))
    throw ParamError("adaptive_fraction", "must be in (0, 1]");
  if (!(min_sobel_threshold >= 0.0 && min_sobel_threshold <= 255.0))
    throw ParamError("min_sobel_threshold", "must be in [0, 255]");
  if (region_dilation_px < 0 || region_dilation_px > 50) throw ParamError("region_dilation_px", "must be 0..50");
  if (!(noise_factor >= 0.0)) throw ParamError("noise_factor", "must be >= 0");
}

EdgeFilter::EdgeFilter(Params params) : params_(params) { params_.validate(); }

EdgeFilter::Result EdgeFilter::filter(const Image& left, const CameraInfo& camera, const StereoCloud& board_cloud,
                                      const Plane& plane_camera, const Target& target) const {
  target.validate();
  if (board_cloud.pixels.size() != board_cloud.points.size())
    throw ParamError("board_cloud", "points and pixels differ in count");
  detail::check_image(left, camera, "left");
  const cv::Mat image = params_.colour && left.channels == 3 ? detail::pixel_mat(left, "left")
                                                             : detail::gray_mat(left, "left");
  Result result;
  result.input_points = board_cloud.size();
  const EdgePixels found = edge_pixels(image, camera, board_cloud, plane_camera, params_);
  result.sobel_threshold = found.threshold;
  result.edge_points = found.points.size();
  const std::vector<bool> removed = border_line_points(board_plane_uv(found.points, plane_camera),
                                                       board_plane_uv(board_cloud.points, plane_camera), target,
                                                       params_, result);
  for (std::size_t k = 0; k < found.points.size(); ++k) {
    if (removed[k]) continue;
    result.edges.points.push_back(found.points[k]);
    result.edges.pixels.push_back(found.pixels[k]);
    result.gradients.push_back(found.gradients[k]);
  }
  result.found = !result.edges.points.empty();
  if (!result.found)
    result.reason = result.edge_points == 0 ? "no image edge in the board's region"
                                            : "only border-line points were on edges";
  return result;
}

}  // namespace l2s
