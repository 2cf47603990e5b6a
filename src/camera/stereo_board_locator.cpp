// The coarse pass of the camera branch (see stereo_board_locator.hpp). The
// scale is chosen from the image width, with a floor that keeps the board
// large enough to be segmented at the far end of the working range; the
// coarse cloud is segmented like the full one, with thresholds widened for
// its coarser depth; each board-sized candidate becomes a region of the left
// image and a depth band for the full-resolution pass.
#include <l2s/stereo_board_locator.hpp>

#include <l2s/error.hpp>

#include "camera/stereo_cloud_subset.hpp"
#include "detail/input_checks.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace l2s {
namespace {

using detail::subset;

double quantile(std::vector<double> values, double q) {
  const std::size_t k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace

PlaneSegmenter::Params StereoBoardLocator::Params::coarse_plane() {
  // The thresholds grow with the coarse pass's depth noise (set per frame).
  PlaneSegmenter::Params plane = PlaneSegmenter::Params::stereo();
  plane.max_samples = 20000;
  // A plain board leaves parts of itself unmatched, and SGM carries its
  // disparity some way into a plain background: the coarse patch may be
  // smaller or larger than the board. The full-resolution pass of its region
  // (widened to the whole board) and the verification decide.
  plane.min_length_fraction = 0.5;
  plane.size_tolerance = 0.5;
  plane.keep_oversized = true;
  return plane;
}

void StereoBoardLocator::Params::validate() const {
  if (!(coarse_width >= 160.0)) throw ParamError("coarse_width", "must be >= 160 px");
  if (!(min_board_px > 0.0)) throw ParamError("min_board_px", "must be > 0 px");
  if (coarse_stride < 1) throw ParamError("coarse_stride", "must be >= 1");
  if (!(region_margin >= 0.0)) throw ParamError("region_margin", "must be >= 0 m");
  if (!(depth_margin > 0.0)) throw ParamError("depth_margin", "must be > 0 m");
  try {
    plane.validate();
  } catch (const ParamError& error) {
    throw ParamError("plane." + error.field(), error.problem());
  }
}

StereoBoardLocator::StereoBoardLocator() : StereoBoardLocator(Params{}) {}

StereoBoardLocator::StereoBoardLocator(Params params) : params_(std::move(params)) { params_.validate(); }

StereoBoardLocator::Result StereoBoardLocator::match_coarse(const Image& left, const Image& right,
                                                            const StereoCamera& cameras, const Target& target,
                                                            const StereoMatcher::Params& stereo,
                                                            const PassThroughFilter::Params& pass_through) const {
  target.validate();
  detail::check_stereo_images(left, right, cameras);
  Result result;
  const double board_short = std::min(target.board_width, target.board_height);
  const double by_width = params_.coarse_width / std::max(1, left.width);
  const double by_board = params_.min_board_px * stereo.max_depth / (cameras.left.fx() * board_short);
  result.scale = std::clamp(std::max(by_width, by_board), 0.1, 1.0);

  StereoMatcher::Params coarse = stereo;
  coarse.downscale = result.scale;
  coarse.row_downscale = 1.0;
  coarse.roi = PixelRect{};
  coarse.stride = params_.coarse_stride;
  result.stereo = StereoMatcher(coarse).match(left, right, cameras);
  if (!result.stereo.found) {
    result.reason = "coarse stereo: " + result.stereo.reason;
    return result;
  }
  result.pass_through = PassThroughFilter(pass_through).filter(result.stereo.cloud.points);
  result.cloud = subset(result.stereo.cloud, result.pass_through.kept);
  return result;
}

StereoBoardLocator::Result StereoBoardLocator::locate(const Image& left, const Image& right,
                                                      const StereoCamera& cameras, const Target& target,
                                                      const StereoMatcher::Params& stereo,
                                                      const PassThroughFilter::Params& pass_through) const {
  Result result = match_coarse(left, right, cameras, target, stereo, pass_through);
  if (!result.stereo.found) return result;
  const double board_short = std::min(target.board_width, target.board_height);
  PlaneSegmenter::Params plane = params_.plane;
  plane.depth_noise = result.stereo.depth_noise;
  result.plane = PlaneSegmenter(plane).segment(result.cloud.points, target);
  if (!result.plane.found) {
    result.reason = "coarse plane: " + result.plane.reason;
    return result;
  }

  // Each candidate's region: its pixels' bounding box, widened by the margin
  // and by as much of the board as the patch may miss (at its nearest
  // depth), and by one coarse cell; its depth band likewise.
  const double cell = 1.0 / result.scale;
  const double board_long = std::max(target.board_width, target.board_height);
  for (const int index : result.plane.ranking) {
    const PlaneCandidate& candidate = result.plane.candidates[index];
    std::vector<double> depths;
    int x0 = left.width, y0 = left.height, x1 = 0, y1 = 0;
    for (const std::size_t i : candidate.inliers) {
      depths.push_back(result.cloud.points[i].z());
      const Eigen::Vector2i& px = result.cloud.pixels[i];
      x0 = std::min(x0, px.x()), y0 = std::min(y0, px.y());
      x1 = std::max(x1, px.x()), y1 = std::max(y1, px.y());
    }
    Region region;
    region.candidate = index;
    region.min_depth = std::max(0.05, quantile(depths, 0.01) - params_.depth_margin);
    region.max_depth = quantile(depths, 0.99) + params_.depth_margin;
    const double missing = std::max({0.0, board_long - candidate.extent_long, board_short - candidate.extent_short});
    const int margin = static_cast<int>(
        std::ceil(cameras.left.fx() * (params_.region_margin + missing) / region.min_depth + cell));
    region.roi.x = std::max(0, x0 - margin);
    region.roi.y = std::max(0, y0 - margin);
    region.roi.width = std::min(left.width, x1 + margin + 1) - region.roi.x;
    region.roi.height = std::min(left.height, y1 + margin + 1) - region.roi.y;
    result.regions.push_back(region);
  }
  result.found = !result.regions.empty();
  return result;
}

}  // namespace l2s
