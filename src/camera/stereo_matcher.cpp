// Stereo matching (paper Sec. III-A): Semi-Global Matching (Hirschmuller
// 2008) through cv::StereoSGBM, then triangulation in the left optical frame.
// Cost is proportional to pixels x disparities, so the search range should be
// the pass-through depth range and nothing more; `downscale` and `roi` trade
// resolution and field of view for speed.

#include <l2s/stereo_matcher.hpp>

#include "camera/cv_image.hpp"

#include <opencv2/calib3d.hpp>

#include <chrono>
#include <cmath>
#include <limits>

namespace l2s {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

int sgbm_mode(StereoMatcher::Mode mode) {
  switch (mode) {
    case StereoMatcher::Mode::Sgbm5: return cv::StereoSGBM::MODE_SGBM;
    case StereoMatcher::Mode::Hh8: return cv::StereoSGBM::MODE_HH;
    case StereoMatcher::Mode::Sgbm3Way: return cv::StereoSGBM::MODE_SGBM_3WAY;
    case StereoMatcher::Mode::Hh4: return cv::StereoSGBM::MODE_HH4;
  }
  return cv::StereoSGBM::MODE_SGBM_3WAY;
}

/// The SGBM search in matched (scaled) pixels: [min_d, min_d + num_d).
struct Search {
  int min_d = 0;
  int num_d = 16;
  int widening = 0;  // [px] full-resolution columns needed left of the region
};

/// Reaches the guard band and two more matched pixels beyond the requested
/// window on each side, so a match SGBM clamps to its search's edge lies
/// outside the window.
Search search_for(double min_disparity, double max_disparity, double guard_px, double scale) {
  Search search;
  search.min_d = std::max(0, static_cast<int>(std::floor((min_disparity - guard_px) * scale)) - 2);
  const int top = static_cast<int>(std::ceil((max_disparity + guard_px) * scale)) + 3;
  search.num_d = ((top - search.min_d + 15) / 16) * 16;
  search.widening = static_cast<int>(std::ceil((search.min_d + search.num_d) / scale));
  return search;
}

void run_sgbm(const StereoMatcher::Params& params, const cv::Mat& left_gray, const cv::Mat& right_gray,
              const cv::Rect& roi, StereoMatcher::Result& result) {
  // Columns and rows scale apart: the disparity is measured along the rows,
  // and SGBM's sub-pixel step locks to whole pixels of the matched images, so
  // coarser columns make coarser depth steps. Averaging rows (row_downscale)
  // costs no depth resolution.
  const double s = params.downscale;
  const double s_rows = s * params.row_downscale;
  const Search search = search_for(result.min_disparity, result.max_disparity, params.guard_px, s);
  // SGBM needs the search's width of columns left of each left pixel to find
  // its match, so the crop is widened to the left and the margin dropped after.
  const int crop_x0 = std::max(0, roi.x - search.widening);
  const cv::Rect crop(crop_x0, roi.y, roi.x + roi.width - crop_x0, roi.height);
  cv::Mat l = left_gray(crop), r = right_gray(crop);
  if (s < 1.0 || s_rows < 1.0) {
    cv::resize(l, l, cv::Size(), s, s_rows, cv::INTER_AREA);
    cv::resize(r, r, cv::Size(), s, s_rows, cv::INTER_AREA);
  }
  const int block_area = params.block_size * params.block_size;
  const int p1 = params.p1 > 0 ? params.p1 : 8 * block_area;
  const int p2 = params.p2 > 0 ? params.p2 : 32 * block_area;
  auto sgbm = cv::StereoSGBM::create(search.min_d, search.num_d, params.block_size, p1, p2,
                                     params.disp12_max_diff, params.pre_filter_cap,
                                     params.uniqueness_ratio, params.speckle_window_size,
                                     params.speckle_range, sgbm_mode(params.mode));
  const auto match_start = Clock::now();
  cv::Mat disparity16;
  sgbm->compute(l, r, disparity16);
  result.match_ms = ms_since(match_start);

  const int skip = static_cast<int>(std::lround((roi.x - crop_x0) * s));
  DisparityMap& map = result.disparity;
  map.width = disparity16.cols - skip;
  map.height = disparity16.rows;
  map.x0 = roi.x;
  map.y0 = roi.y;
  map.scale = s;
  map.row_scale = s_rows;
  map.values.assign(static_cast<std::size_t>(map.width) * map.height, std::numeric_limits<float>::quiet_NaN());
  // Only the window is a measurement: values outside it are matches SGBM
  // clamped to its search's edge (the true match lies beyond the working range).
  const float to_full = static_cast<float>(1.0 / (16.0 * s));  // fixed point 1/16 px, then rescale
  for (int j = 0; j < map.height; ++j) {
    const auto* row = disparity16.ptr<std::int16_t>(j) + skip;
    float* out = map.values.data() + static_cast<std::size_t>(j) * map.width;
    for (int i = 0; i < map.width; ++i) {
      if (row[i] < search.min_d * 16) continue;  // invalid = (min_d - 1) * 16
      const double d = row[i] * to_full;
      if (d < result.min_disparity || d > result.max_disparity) {
        ++result.window_edge;
        continue;
      }
      out[i] = static_cast<float>(d);
    }
  }
}

void triangulate(const StereoMatcher::Params& params, const StereoCamera& camera, double d_infinity,
                 StereoMatcher::Result& result) {
  const DisparityMap& map = result.disparity;
  const double fx = camera.left.fx(), fy = camera.left.fy();
  const double cx = camera.left.cx(), cy = camera.left.cy();
  const double fb = fx * camera.baseline();
  StereoCloud& cloud = result.cloud;
  cloud.points.reserve(map.values.size() / (params.stride * params.stride));
  cloud.pixels.reserve(cloud.points.capacity());
  for (int j = 0; j < map.height; j += params.stride) {
    const double v = map.y0 + (j + 0.5) / map.row_scale - 0.5;
    for (int i = 0; i < map.width; i += params.stride) {
      const float d = map.at(i, j);
      if (!std::isfinite(d)) continue;
      const double z = fb / (d - d_infinity);
      if (!(z >= params.min_depth && z <= params.max_depth)) continue;
      const double u = map.x0 + (i + 0.5) / map.scale - 0.5;
      cloud.points.emplace_back((u - cx) * z / fx, (v - cy) * z / fy, z);
      cloud.pixels.emplace_back(static_cast<int>(std::lround(u)), static_cast<int>(std::lround(v)));
    }
  }
}

}  // namespace

void StereoMatcher::Params::validate() const {
  if (block_size < 1 || block_size > 11 || block_size % 2 == 0)
    throw ParamError("block_size", "must be odd, 1..11");
  if (p1 < 0) throw ParamError("p1", "must be >= 0 (0 = automatic)");
  if (p2 < 0 || (p2 > 0 && p2 <= p1)) throw ParamError("p2", "must be > p1 (0 = automatic)");
  if (pre_filter_cap < 1 || pre_filter_cap > 63) throw ParamError("pre_filter_cap", "must be 1..63");
  if (uniqueness_ratio < 0 || uniqueness_ratio > 100)
    throw ParamError("uniqueness_ratio", "must be 0..100");
  if (speckle_window_size < 0) throw ParamError("speckle_window_size", "must be >= 0");
  if (speckle_range < 0) throw ParamError("speckle_range", "must be >= 0");
  if (!(downscale > 0.0 && downscale <= 1.0)) throw ParamError("downscale", "must be in (0, 1]");
  if (!(row_downscale > 0.0 && row_downscale <= 1.0)) throw ParamError("row_downscale", "must be in (0, 1]");
  if (!(guard_px >= 0.0)) throw ParamError("guard_px", "must be >= 0 px");
  if (!(disparity_sigma > 0.0)) throw ParamError("disparity_sigma", "must be > 0 px");
  if (roi.x < 0 || roi.y < 0 || roi.width < 0 || roi.height < 0)
    throw ParamError("roi", "must have non-negative origin and size");
  if (!(min_depth > 0.0)) throw ParamError("min_depth", "must be > 0");
  if (!(max_depth > min_depth)) throw ParamError("max_depth", "must be > min_depth");
  if (stride < 1) throw ParamError("stride", "must be >= 1");
}

StereoMatcher::StereoMatcher(Params params) : params_(params) { params_.validate(); }

StereoMatcher::Result StereoMatcher::match(const Image& left, const Image& right,
                                           const StereoCamera& camera) const {
  const auto start = Clock::now();
  Result result;
  detail::check_stereo_images(left, right, camera);
  const cv::Mat left_gray = detail::gray_mat(left, "left");
  const cv::Mat right_gray = detail::gray_mat(right, "right");
  const double baseline = camera.baseline();
  if (!(std::isfinite(baseline) && baseline > 0.0)) {
    result.reason = "stereo baseline is not positive";
    return result;
  }
  cv::Rect roi(0, 0, left.width, left.height);
  if (!params_.roi.empty())
    roi = cv::Rect(params_.roi.x, params_.roi.y, params_.roi.width, params_.roi.height) & roi;
  if (roi.area() <= 0) {
    result.reason = "region of interest lies outside the image";
    return result;
  }
  // The window of the working range on this rig. When the right principal
  // point differs, the disparity of a point at infinity is cx_left - cx_right.
  const double fb = camera.left.fx() * baseline;
  const double d_infinity = camera.left.cx() - camera.right.cx();
  result.depth_noise = params_.disparity_sigma / (params_.downscale * fb);
  result.min_disparity = fb / params_.max_depth + d_infinity;
  result.max_disparity = fb / params_.min_depth + d_infinity;
  if (!(result.max_disparity > 0.0) || result.min_disparity >= left.width) {
    result.reason = "the depth range lies outside what this rig can match";
    return result;
  }
  run_sgbm(params_, left_gray, right_gray, roi, result);
  triangulate(params_, camera, d_infinity, result);
  result.found = !result.cloud.points.empty();
  if (!result.found) result.reason = "no pixel matched inside the depth range";
  result.total_ms = ms_since(start);
  return result;
}

}  // namespace l2s
