// Hole rims from the board's occupancy in its plane (see the header).
//  1. Board points in plane coordinates; their mean spacing from their
//     density over the board's solid area sets the grid cell.
//  2. One-cell gaps in the coverage are filled (occupied on both sides). A
//     hole's centre is a place about a radius from the nearest board point
//     (distance transform of the empty cells) with board all around; gaps in
//     a non-repetitive scan's coverage are narrow, the outside is open. A
//     hole the field of view cuts is open too: two holes found at the
//     pattern's spacing predict it, and a rim arc there confirms it.
//  3. Around each hole (centre: its distance peak), the innermost board
//     point in each direction (sectors two point spacings wide at the rim)
//     is a rim point, moved half a spacing inwards. Strays inside a hole sit
//     farther in and are ignored when nearer than half a radius; the circle
//     finder's fit (free apparent radius) does the rest.
#include <l2s/occupancy_edge_filter.hpp>

#include <l2s/error.hpp>

#include "detail/plane_frame.hpp"
#include "lidar/hole_completion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>

namespace l2s {
namespace {

/// A regular grid of cells over the board points' bounding box, one cell of margin.
class OccupancyGrid {
 public:
  OccupancyGrid(const std::vector<Eigen::Vector2d>& uv, double cell) : cell_(cell) {
    Eigen::AlignedBox2d box;
    for (const auto& q : uv) box.extend(q);
    origin_ = box.min() - Eigen::Vector2d::Constant(cell);
    width_ = static_cast<int>(std::ceil(box.sizes().x() / cell)) + 3;
    height_ = static_cast<int>(std::ceil(box.sizes().y() / cell)) + 3;
    count_.assign(static_cast<std::size_t>(width_) * height_, 0);
    for (const auto& q : uv) ++count_[index(cell_of(q))];
  }

  /// Fills empty cells that have occupied cells on both sides (along a row,
  /// a column or a diagonal): a non-repetitive scan leaves such one-cell
  /// gaps in its coverage, a hole is many cells across.
  void close_gaps() {
    std::vector<int> filled = count_;
    for (int y = 1; y + 1 < height_; ++y)
      for (int x = 1; x + 1 < width_; ++x) {
        if (!empty(x, y)) continue;
        const bool across = (!empty(x - 1, y) && !empty(x + 1, y)) || (!empty(x, y - 1) && !empty(x, y + 1)) ||
                            (!empty(x - 1, y - 1) && !empty(x + 1, y + 1)) ||
                            (!empty(x - 1, y + 1) && !empty(x + 1, y - 1));
        if (across) filled[static_cast<std::size_t>(y) * width_ + x] = 1;
      }
    count_.swap(filled);
  }

  Eigen::Vector2i cell_of(const Eigen::Vector2d& q) const {
    return ((q - origin_) / cell_).array().floor().cast<int>();
  }
  Eigen::Vector2d centre_of(int x, int y) const { return origin_ + cell_ * Eigen::Vector2d(x + 0.5, y + 0.5); }
  std::size_t index(const Eigen::Vector2i& c) const { return static_cast<std::size_t>(c.y()) * width_ + c.x(); }
  bool empty(int x, int y) const { return count_[static_cast<std::size_t>(y) * width_ + x] == 0; }
  int width() const { return width_; }
  int height() const { return height_; }
  double cell() const { return cell_; }

 private:
  double cell_;
  Eigen::Vector2d origin_;
  int width_ = 0, height_ = 0;
  std::vector<int> count_;
};

/// [cells] each cell's distance to the nearest occupied cell (0 when occupied).
cv::Mat empty_distance(const OccupancyGrid& grid) {
  cv::Mat empty(grid.height(), grid.width(), CV_8UC1);
  for (int y = 0; y < grid.height(); ++y)
    for (int x = 0; x < grid.width(); ++x) empty.at<std::uint8_t>(y, x) = grid.empty(x, y) ? 255 : 0;
  cv::Mat distance;
  cv::distanceTransform(empty, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance;
}

/// Hole centres: places of the grid that are far from every board point
/// (local maxima of the distance to the nearest occupied cell, about a
/// radius) and surrounded by board in every direction. Gaps in a scan's
/// coverage are narrow, so they stay near board; the outside is not
/// surrounded.
std::vector<Eigen::Vector2d> hole_centres(const OccupancyGrid& grid, const cv::Mat& distance, double radius,
                                          double min_depth) {
  const int w = grid.width(), h = grid.height();
  const double cell = grid.cell();
  const auto surrounded = [&](int x, int y) {
    const int reach = static_cast<int>(std::ceil(1.6 * radius / cell));
    for (int k = 0; k < 8; ++k) {
      const double a = k * M_PI / 4.0;
      bool hit = false;
      for (int step = 1; step <= reach && !hit; ++step) {
        const int xx = x + static_cast<int>(std::lround(step * std::cos(a)));
        const int yy = y + static_cast<int>(std::lround(step * std::sin(a)));
        if (xx < 0 || yy < 0 || xx >= w || yy >= h) return false;
        hit = !grid.empty(xx, yy);
      }
      if (!hit) return false;
    }
    return true;
  };
  std::vector<std::pair<float, Eigen::Vector2i>> peaks;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const float d = distance.at<float>(y, x);
      if (d * cell < min_depth * radius || d * cell > 1.5 * radius) continue;
      bool peak = true;
      for (int dy = -1; dy <= 1 && peak; ++dy)
        for (int dx = -1; dx <= 1 && peak; ++dx) peak = distance.at<float>(y + dy, x + dx) <= d;
      if (peak && surrounded(x, y)) peaks.emplace_back(d, Eigen::Vector2i(x, y));
    }
  std::stable_sort(peaks.begin(), peaks.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Eigen::Vector2d> centres;
  for (const auto& [d, c] : peaks) {
    const Eigen::Vector2d q = grid.centre_of(c.x(), c.y());
    if (std::none_of(centres.begin(), centres.end(), [&](const auto& k) { return (k - q).norm() < radius; }))
      centres.push_back(q);
  }
  return centres;
}

/// The innermost board point per direction around `centre`, between half and
/// one and a half radii out. A sector as wide as two point spacings at the
/// rim holds its nearest point about half a spacing beyond the rim.
std::vector<std::size_t> rim_points(const std::vector<Eigen::Vector2d>& uv, const Eigen::Vector2d& centre,
                                    double radius, int sectors) {
  std::vector<std::size_t> best(static_cast<std::size_t>(sectors), std::numeric_limits<std::size_t>::max());
  std::vector<double> nearest(static_cast<std::size_t>(sectors), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < uv.size(); ++i) {
    const Eigen::Vector2d d = uv[i] - centre;
    const double r = d.norm();
    if (r < 0.5 * radius || r > 1.5 * radius) continue;
    const double angle = std::atan2(d.y(), d.x()) + M_PI;
    const auto s = std::min(sectors - 1, static_cast<int>(angle / (2.0 * M_PI) * sectors));
    if (r < nearest[s]) nearest[s] = r, best[s] = i;
  }
  std::vector<std::size_t> out;
  for (const std::size_t i : best)
    if (i != std::numeric_limits<std::size_t>::max()) out.push_back(i);
  return out;
}

/// The holes found, and those the hole pattern adds (hole_completion.hpp): a
/// place two found holes predict is a hole when it is empty a hole's depth
/// around and at least a third of the directions from it meet board a
/// radius away (within a fifth of it): a rim arc. A hole cut by the field of
/// view keeps the arc on its scanned side; a place beside the board's
/// straight edge meets it at a radius in too few directions.
std::vector<Eigen::Vector2d> with_pattern_holes(std::vector<Eigen::Vector2d> centres,
                                                const std::vector<Eigen::Vector2d>& uv, const OccupancyGrid& grid,
                                                const cv::Mat& distance, const Target& target, double min_depth,
                                                int sectors) {
  const double r = target.hole_radius;
  for (const Eigen::Vector2d& q :
       detail::predicted_holes(centres, target.hole_spacing_x, target.hole_spacing_y, 0.25 * r)) {
    if (std::any_of(centres.begin(), centres.end(), [&](const auto& k) { return (k - q).norm() < r; })) continue;
    const Eigen::Vector2i c = grid.cell_of(q);
    if (c.x() < 0 || c.y() < 0 || c.x() >= grid.width() || c.y() >= grid.height()) continue;
    if (distance.at<float>(c.y(), c.x()) * grid.cell() < min_depth * r) continue;
    const auto rim = rim_points(uv, q, r, sectors);
    const auto on_arc = std::count_if(rim.begin(), rim.end(),
                                      [&](std::size_t k) { return std::abs((uv[k] - q).norm() - r) < 0.2 * r; });
    if (3 * on_arc >= sectors) centres.push_back(q);
  }
  return centres;
}

}  // namespace

std::string OccupancyEdgeFilter::Result::cut_board_hint(const Target& target) const {
  if (holes >= 4 || board_points == 0) return {};
  // The board's sides as the sensor sees them, whichever way it stands.
  const double wide = std::max(target.board_width, target.board_height);
  const double tall = std::min(target.board_width, target.board_height);
  const double seen_wide = std::max(seen_width, seen_height), seen_tall = std::min(seen_width, seen_height);
  if (seen_wide >= wide - target.hole_radius && seen_tall >= tall - target.hole_radius) return {};
  std::ostringstream hint;
  hint.precision(2);
  hint << std::fixed << "only " << holes << " of 4 holes in the board's occupancy, and the board is seen over "
       << seen_width << " x " << seen_height << " m of its " << target.board_width << " x " << target.board_height
       << " m: the edge of the field of view (or something in front) cuts it; aim the lidar so that the whole "
          "board is in view";
  return hint.str();
}

void OccupancyEdgeFilter::Params::validate() const {
  if (!(cell_factor > 0.0)) throw ParamError("cell_factor", "must be > 0");
  if (!(min_cell > 0.0)) throw ParamError("min_cell", "must be > 0 m");
  if (!(max_cell >= min_cell)) throw ParamError("max_cell", "must be >= min_cell");
  if (!(min_hole_depth > 0.0 && min_hole_depth < 1.5)) throw ParamError("min_hole_depth", "must be in (0, 1.5)");
  if (rim_sectors < 8) throw ParamError("rim_sectors", "must be >= 8");
}

OccupancyEdgeFilter::OccupancyEdgeFilter() : OccupancyEdgeFilter(Params{}) {}

OccupancyEdgeFilter::OccupancyEdgeFilter(Params params) : params_(params) { params_.validate(); }

OccupancyEdgeFilter::Result OccupancyEdgeFilter::filter(const std::vector<Eigen::Vector3d>& points,
                                                        const Plane& plane,
                                                        const std::vector<std::size_t>& board_inliers,
                                                        const Eigen::Vector3d& up, const Target& target) const {
  target.validate();
  Result result;
  std::vector<std::size_t> board;
  for (const std::size_t i : board_inliers) {
    if (i >= points.size()) throw ParamError("board_inliers", "index past the end of the points");
    if (points[i].allFinite()) board.push_back(i);
  }
  result.board_points = board.size();
  const double hole_area = M_PI * target.hole_radius * target.hole_radius;
  const double solid_area = target.board_width * target.board_height - 4.0 * hole_area;
  if (board.size() < 50) {
    result.reason = "only " + std::to_string(board.size()) +
                    " board points: too sparse to see holes (accumulate more sweeps of the static board)";
    return result;
  }
  const auto frame = detail::PlaneFrame::make(plane, up, detail::centroid(points, board));
  std::vector<Eigen::Vector2d> uv;
  uv.reserve(board.size());
  for (const std::size_t i : board) uv.push_back(frame.to_plane(points[i]));

  Eigen::AlignedBox2d seen;
  for (const Eigen::Vector2d& q : uv) seen.extend(q);
  result.seen_width = seen.sizes().x();
  result.seen_height = seen.sizes().y();
  const double spacing = std::sqrt(solid_area / static_cast<double>(board.size()));
  result.cell = std::clamp(params_.cell_factor * spacing, params_.min_cell, params_.max_cell);
  OccupancyGrid grid(uv, result.cell);
  grid.close_gaps();
  const cv::Mat distance = empty_distance(grid);
  const int sectors = std::clamp(static_cast<int>(M_PI * target.hole_radius / spacing), 8, params_.rim_sectors);
  const auto found = hole_centres(grid, distance, target.hole_radius, params_.min_hole_depth);
  for (const Eigen::Vector2d& centre :
       with_pattern_holes(found, uv, grid, distance, target, params_.min_hole_depth, sectors)) {
    ++result.holes;
    // Each rim point is moved half a spacing in, onto the rim it stands for.
    for (const std::size_t k : rim_points(uv, centre, target.hole_radius, sectors)) {
      const Eigen::Vector2d inward = (centre - uv[k]).normalized() * 0.5 * spacing;
      result.edges.push_back(frame.to_sensor(uv[k] + inward) + frame.height(points[board[k]]) * frame.normal);
    }
  }
  result.found = !result.edges.empty();
  if (!result.found) {
    std::ostringstream reason;
    reason << "no hole in the board's occupancy: " << result.board_points << " board points, cell "
           << result.cell * 1e3 << " mm, no place a hole's depth away from board points and surrounded by them";
    // Points farther apart than the coarsest cell leave gaps as wide as the
    // holes: the board was not scanned long enough, which the user can mend.
    const double widest_spacing = params_.max_cell / params_.cell_factor;
    if (spacing > widest_spacing) {
      const double more = std::pow(spacing / widest_spacing, 2);
      result.sparse_factor = more;
      reason.precision(1);
      reason << std::fixed << " (the board's points are " << spacing * 1e3 << " mm apart on average, too sparse for "
             << "holes of radius " << target.hole_radius * 1e3 << " mm: accumulate at least " << more
             << " times as many sweeps of the static board)";
    }
    result.reason = reason.str();
  }
  return result;
}

}  // namespace l2s
