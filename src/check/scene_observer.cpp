// The observations of one frame for the calibration check
// (scene_observer.hpp): lidar discontinuities split into board and scene,
// thinned returns, image edge distances and coarse stereo depth.

#include <l2s/scene_observer.hpp>

#include "camera/cv_image.hpp"
#include "camera/noise_level.hpp"
#include "check/image_edges.hpp"
#include "check/lidar_discontinuities.hpp"
#include "plane/plane_fit.hpp"

#include <opencv2/imgproc.hpp>

#include <l2s/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace l2s {
namespace {

/// At most `limit` elements of `points`, evenly spread over their order.
std::vector<Eigen::Vector3d> thinned(const std::vector<Eigen::Vector3d>& points, int limit) {
  if (static_cast<int>(points.size()) <= limit) return points;
  std::vector<Eigen::Vector3d> out;
  out.reserve(limit);
  const double stride = static_cast<double>(points.size()) / limit;
  for (int k = 0; k < limit; ++k) out.push_back(points[static_cast<std::size_t>(k * stride)]);
  return out;
}

/// The lidar board's plane and extent: a discontinuity within `band` of the
/// plane and inside the extent (plus the band) lies on the board.
class BoardRegion {
 public:
  BoardRegion(const std::vector<Eigen::Vector3d>& board, double band) : band_(band) {
    if (board.size() < 3) return;
    std::vector<std::size_t> all(board.size());
    std::iota(all.begin(), all.end(), 0);
    plane_ = detail::fit_plane(board, all);
    center_ = Eigen::Vector3d::Zero();
    for (const auto& p : board) center_ += p / static_cast<double>(board.size());
    for (const auto& p : board) radius_ = std::max(radius_, in_plane(p));
    valid_ = true;
  }
  bool contains(const Eigen::Vector3d& p) const {
    return valid_ && std::abs(plane_.signedDistance(p)) <= band_ && in_plane(p) <= radius_ + band_;
  }

 private:
  double in_plane(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - center_;
    return (d - d.dot(plane_.normal()) * plane_.normal()).norm();
  }
  bool valid_ = false;
  double band_;
  Plane plane_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  double radius_ = 0.0;
};

/// Clears the cells within `margin_px` of a depth jump (10 %): SGBM's
/// window carries a near surface's disparity a few pixels over the far one
/// beside it (foreground fattening), so stereo there is biased towards the
/// camera.
void drop_near_jumps(DepthMap& map, double margin_px) {
  const int radius = static_cast<int>(std::ceil(margin_px / map.cell));
  if (radius <= 0 || map.empty()) return;
  cv::Mat depth(map.height, map.width, CV_32F, map.depth.data());
  cv::Mat valid = depth == depth;  // NaN compares unequal
  cv::Mat low = depth.clone(), high = depth.clone();
  low.setTo(1e9f, ~valid);
  high.setTo(0.0f, ~valid);
  const cv::Mat window = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * radius + 1, 2 * radius + 1));
  cv::erode(low, low, window);
  cv::dilate(high, high, window);
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      float& z = map.depth[static_cast<std::size_t>(j) * map.width + i];
      if (std::isfinite(z) && high.at<float>(j, i) - low.at<float>(j, i) > 0.1f * z)
        z = std::numeric_limits<float>::quiet_NaN();
    }
}

constexpr int kMatchWindow = 5;  // [px] SGBM's default block: the texture a match rests on

/// [Sobel magnitude] Twice the mean |Sobel| of the image's noise averaged
/// over a matching window: a window whose gradient stays below it holds
/// nothing but noise for stereo to match.
double texture_floor(const cv::Mat& gray) {
  constexpr double kNoiseMeanPerSigma = 2.76;  // mean |Sobel| of pure noise: 0.8 * sqrt(12) sigma
  return 2.0 * kNoiseMeanPerSigma * detail::image_noise_sigma(gray);
}

}  // namespace

double EdgeDistanceMap::at(double u, double v) const {
  const long x = std::lround(u), y = std::lround(v);
  if (x < 0 || y < 0 || x >= width || y >= height) return std::numeric_limits<double>::infinity();
  return unit * distance[static_cast<std::size_t>(y) * width + x];
}

long DepthMap::cell_index(double u, double v) const {
  const long i = static_cast<long>(std::floor((u + 0.5) / cell)), j = static_cast<long>(std::floor((v + 0.5) / cell));
  if (i < 0 || j < 0 || i >= width || j >= height) return -1;
  return j * width + i;
}

double DepthMap::at(double u, double v) const {
  const long k = cell_index(u, v);
  return k < 0 ? std::numeric_limits<double>::quiet_NaN() : depth[static_cast<std::size_t>(k)];
}

bool DepthMap::textured_at(double u, double v) const {
  if (textured.size() != depth.size()) return true;
  const long k = cell_index(u, v);
  return k >= 0 && textured[static_cast<std::size_t>(k)] != 0;
}

void SceneObserver::Params::validate() const {
  if (!(min_jump > 0.0)) throw ParamError("min_jump", "must be > 0");
  if (!(relative_jump >= 0.0)) throw ParamError("relative_jump", "must be >= 0");
  if (!(gap_factor > 1.0)) throw ParamError("gap_factor", "must be > 1");
  if (!(min_range >= 0.0)) throw ParamError("min_range", "must be >= 0");
  if (!(grid_step > 0.0)) throw ParamError("grid_step", "must be > 0");
  if (!(board_band > 0.0)) throw ParamError("board_band", "must be > 0");
  if (max_edges < 10) throw ParamError("max_edges", "must be >= 10");
  if (max_board_points < 10) throw ParamError("max_board_points", "must be >= 10");
  if (max_scene_points < 10) throw ParamError("max_scene_points", "must be >= 10");
  if (!(canny_low > 0.0)) throw ParamError("canny_low", "must be > 0");
  if (!(canny_high >= canny_low)) throw ParamError("canny_high", "must be >= canny_low");
  if (!(strong_edge > 0.0)) throw ParamError("strong_edge", "must be > 0");
  if (!(depth_cell >= 1.0)) throw ParamError("depth_cell", "must be >= 1");
  if (!(depth_jump_margin >= 0.0)) throw ParamError("depth_jump_margin", "must be >= 0");
}

SceneObserver::SceneObserver() : SceneObserver(Params{}) {}
SceneObserver::SceneObserver(Params params) : params_(params) { params_.validate(); }

LidarObservation SceneObserver::observe_lidar(const LidarCloud& sweep,
                                              const std::vector<Eigen::Vector3d>& board) const {
  const detail::JumpRule rule{params_.min_jump, params_.relative_jump, params_.gap_factor, params_.min_range};
  LidarObservation out;
  out.ring_free = !sweep.has_ring() || sweep.ring.size() != sweep.size();
  const std::vector<Eigen::Vector3d> edges = out.ring_free
                                                 ? detail::grid_discontinuities(sweep, rule, params_.grid_step)
                                                 : detail::ring_discontinuities(sweep, rule);
  const BoardRegion region(board, params_.board_band);
  for (const auto& e : thinned(edges, params_.max_edges)) (region.contains(e) ? out.board_edges : out.scene_edges).push_back(e);
  out.board = thinned(board, params_.max_board_points);
  std::vector<Eigen::Vector3d> finite;
  finite.reserve(sweep.size());
  for (const auto& p : sweep.points)
    if (p.allFinite() && p.norm() >= params_.min_range) finite.push_back(p);
  out.scene = thinned(finite, params_.max_scene_points);
  return out;
}

EdgeDistanceMap SceneObserver::observe_edges(const Image& left, const StereoCamera& cameras) const {
  return detail::edge_distance_map(detail::rectified_left_gray(left, cameras), params_);
}

DepthMap SceneObserver::observe_depth(const DisparityMap& disparity, const StereoCamera& cameras,
                                      double depth_noise) const {
  DepthMap out;
  if (disparity.empty()) return out;
  const double fB = cameras.left.fx() * cameras.baseline();
  const double d_infinity = cameras.left.cx() - cameras.right.cx();  // principal points apart: disparity of a point at infinity
  out.cell = params_.depth_cell;
  out.width = static_cast<int>(std::ceil(cameras.left.width / out.cell));
  out.height = static_cast<int>(std::ceil(cameras.left.height / out.cell));
  out.depth_noise = depth_noise;
  out.depth.assign(static_cast<std::size_t>(out.width) * out.height, std::numeric_limits<float>::quiet_NaN());
  // Each cell takes the disparity cell under its centre (DisparityMap's pixel convention).
  for (int j = 0; j < out.height; ++j)
    for (int i = 0; i < out.width; ++i) {
      const double u = (i + 0.5) * out.cell - 0.5, v = (j + 0.5) * out.cell - 0.5;
      const long di = std::lround((u - disparity.x0 + 0.5) * disparity.scale - 0.5);
      const long dj = std::lround((v - disparity.y0 + 0.5) * disparity.row_scale - 0.5);
      if (di < 0 || dj < 0 || di >= disparity.width || dj >= disparity.height) continue;
      const float d = disparity.at(static_cast<int>(di), static_cast<int>(dj));
      if (std::isfinite(d) && d > d_infinity)
        out.depth[static_cast<std::size_t>(j) * out.width + i] = static_cast<float>(fB / (d - d_infinity));
    }
  drop_near_jumps(out, params_.depth_jump_margin);
  return out;
}

double SceneObserver::row_texture_share(const Image& rectified_left, const StereoCloud& board) const {
  if (board.pixels.empty()) return std::numeric_limits<double>::quiet_NaN();
  const cv::Mat gray = detail::gray_mat(rectified_left, "left");
  // The gradients on the board's bounding box only, averaged over a
  // matching window (SGBM's default 5 px).
  const auto inside = [&](const Eigen::Vector2i& p) {
    return p.x() >= 0 && p.y() >= 0 && p.x() < gray.cols && p.y() < gray.rows;
  };
  cv::Rect box;
  for (const Eigen::Vector2i& p : board.pixels)
    if (inside(p)) box = box.empty() ? cv::Rect(p.x(), p.y(), 1, 1) : box | cv::Rect(p.x(), p.y(), 1, 1);
  if (box.empty()) return std::numeric_limits<double>::quiet_NaN();
  constexpr int kWindow = kMatchWindow;
  const cv::Rect padded = (box + cv::Size(2 * kWindow, 2 * kWindow) - cv::Point(kWindow, kWindow)) &
                          cv::Rect(0, 0, gray.cols, gray.rows);
  cv::Mat across, along;  // the gradient across the rows (d/dy) and along them (d/dx)
  cv::Sobel(gray(padded), across, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(gray(padded), along, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  across = cv::abs(across);
  along = cv::abs(along);
  cv::blur(across, across, cv::Size(kWindow, kWindow));
  cv::blur(along, along, cv::Size(kWindow, kWindow));
  const double noise_floor = texture_floor(gray);
  const std::size_t step = std::max<std::size_t>(1, board.pixels.size() / 4000);
  std::size_t rows_only = 0, sampled = 0;
  for (std::size_t i = 0; i < board.pixels.size(); i += step) {
    if (!inside(board.pixels[i])) continue;
    const int x = board.pixels[i].x() - padded.x, y = board.pixels[i].y() - padded.y;
    const float a = across.at<float>(y, x);
    rows_only += a > noise_floor && along.at<float>(y, x) < 0.5f * a;
    ++sampled;
  }
  return sampled ? static_cast<double>(rows_only) / static_cast<double>(sampled)
                 : std::numeric_limits<double>::quiet_NaN();
}

void SceneObserver::mark_texture(const Image& rectified_left, DepthMap& map) const {
  if (map.empty()) return;
  const cv::Mat gray = detail::gray_mat(rectified_left, "left");
  cv::Mat along;  // |d/dx| averaged over a matching window
  cv::Sobel(gray, along, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
  along = cv::abs(along);
  cv::blur(along, along, cv::Size(kMatchWindow, kMatchWindow));
  const float floor = static_cast<float>(texture_floor(gray));
  map.textured.assign(map.depth.size(), 0);
  // Each cell is judged at the pixel under its centre, as its depth is.
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      const int u = std::min(gray.cols - 1, static_cast<int>(std::lround((i + 0.5) * map.cell - 0.5)));
      const int v = std::min(gray.rows - 1, static_cast<int>(std::lround((j + 0.5) * map.cell - 0.5)));
      map.textured[static_cast<std::size_t>(j) * map.width + i] = along.at<float>(v, u) > floor;
    }
}

}  // namespace l2s
