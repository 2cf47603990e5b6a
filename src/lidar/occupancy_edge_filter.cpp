// Hole rims from the board's occupancy in its plane (see the header).
//  1. Board points in plane coordinates; their mean spacing from their
//     density over the board's solid area sets the grid cell.
//  2. Empty cells are grouped (4-connected); groups touching the grid's
//     border are the outside, the others are enclosed by board: a hole when
//     hole-sized, a gap in the scan's coverage when smaller.
//  3. Around each hole (centre: its cells' centroid), the innermost board
//     point in each direction is a rim point. Strays inside a hole sit
//     farther in and are ignored when nearer than half a radius; the circle
//     finder's fit (free apparent radius) does the rest.
#include <l2s/occupancy_edge_filter.hpp>

#include <l2s/error.hpp>

#include "detail/plane_frame.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

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

/// Enclosed groups of empty cells (4-connected), each as the centres of its cells.
std::vector<std::vector<Eigen::Vector2d>> enclosed_empty_regions(const OccupancyGrid& grid) {
  const int w = grid.width(), h = grid.height();
  std::vector<int> label(static_cast<std::size_t>(w) * h, -1);
  std::vector<std::vector<Eigen::Vector2d>> regions;
  std::vector<Eigen::Vector2i> stack;
  for (int y0 = 0; y0 < h; ++y0)
    for (int x0 = 0; x0 < w; ++x0) {
      if (!grid.empty(x0, y0) || label[static_cast<std::size_t>(y0) * w + x0] >= 0) continue;
      bool touches_border = false;
      std::vector<Eigen::Vector2d> cells;
      stack.assign(1, {x0, y0});
      label[static_cast<std::size_t>(y0) * w + x0] = 1;
      while (!stack.empty()) {
        const Eigen::Vector2i c = stack.back();
        stack.pop_back();
        cells.push_back(grid.centre_of(c.x(), c.y()));
        touches_border |= c.x() == 0 || c.y() == 0 || c.x() == w - 1 || c.y() == h - 1;
        for (const Eigen::Vector2i d : {Eigen::Vector2i(1, 0), Eigen::Vector2i(-1, 0), Eigen::Vector2i(0, 1),
                                        Eigen::Vector2i(0, -1)}) {
          const Eigen::Vector2i n = c + d;
          if (n.x() < 0 || n.y() < 0 || n.x() >= w || n.y() >= h) continue;
          int& l = label[static_cast<std::size_t>(n.y()) * w + n.x()];
          if (l >= 0 || !grid.empty(n.x(), n.y())) continue;
          l = 1;
          stack.push_back(n);
        }
      }
      if (!touches_border) regions.push_back(std::move(cells));
    }
  return regions;
}

/// The innermost board point per direction around `centre`, between half and
/// one and a half radii out.
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

}  // namespace

void OccupancyEdgeFilter::Params::validate() const {
  if (!(cell_factor > 0.0)) throw ParamError("cell_factor", "must be > 0");
  if (!(min_cell > 0.0)) throw ParamError("min_cell", "must be > 0 m");
  if (!(max_cell >= min_cell)) throw ParamError("max_cell", "must be >= min_cell");
  if (!(min_hole_area > 0.0)) throw ParamError("min_hole_area", "must be > 0");
  if (!(max_hole_area > min_hole_area)) throw ParamError("max_hole_area", "must be > min_hole_area");
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
    if (i >= points.size()) throw Error("OccupancyEdgeFilter: board inlier index out of range");
    if (points[i].allFinite()) board.push_back(i);
  }
  result.board_points = board.size();
  const double hole_area = M_PI * target.hole_radius * target.hole_radius;
  const double solid_area = target.board_width * target.board_height - 4.0 * hole_area;
  if (board.size() < 50) {
    result.reason = "only " + std::to_string(board.size()) + " board points: too sparse to see holes";
    return result;
  }
  const auto frame = detail::PlaneFrame::make(plane, up, detail::centroid(points, board));
  std::vector<Eigen::Vector2d> uv;
  uv.reserve(board.size());
  for (const std::size_t i : board) uv.push_back(frame.to_plane(points[i]));

  const double spacing = std::sqrt(solid_area / static_cast<double>(board.size()));
  result.cell = std::clamp(params_.cell_factor * spacing, params_.min_cell, params_.max_cell);
  const OccupancyGrid grid(uv, result.cell);
  const auto regions = enclosed_empty_regions(grid);
  result.enclosed_regions = static_cast<int>(regions.size());
  const double cell_area = result.cell * result.cell;
  for (const auto& cells : regions) {
    const double area = static_cast<double>(cells.size()) * cell_area;
    if (area < params_.min_hole_area * hole_area || area > params_.max_hole_area * hole_area) continue;
    ++result.holes;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& c : cells) centre += c / static_cast<double>(cells.size());
    for (const std::size_t k : rim_points(uv, centre, target.hole_radius, params_.rim_sectors))
      result.edges.push_back(points[board[k]]);
  }
  result.found = !result.edges.empty();
  if (!result.found) {
    std::ostringstream reason;
    reason << "no hole in the board's occupancy: " << result.board_points << " board points, cell "
           << result.cell * 1e3 << " mm, " << result.enclosed_regions << " enclosed empty region(s), none hole-sized";
    result.reason = reason.str();
  }
  return result;
}

}  // namespace l2s
