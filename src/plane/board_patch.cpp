// Connected patches on a plane, for telling the board from larger coplanar
// surfaces (a wall behind it) or scattered junk. The cells are anisotropic:
// a lidar samples the board densely along a ring but only at ring heights.
#include "plane/board_patch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace l2s::detail {
namespace {

constexpr int kDirections = 90;   // 1-degree steps for the smallest enclosing rectangle
constexpr double kBin = 0.05;      // [m] resolution of the board-window search
constexpr int kMaxBins = 400;      // larger patches are walls: no window search
constexpr double kSparseCellShare = 0.2;  // cells below this share of the dense cells' count are strays

/// The window position holding most points (summed-area table on kBin bins).
Eigen::AlignedBox2d best_window(const std::vector<Eigen::Vector2d>& uv, const Eigen::Vector2d& size,
                                std::size_t* count) {
  Eigen::AlignedBox2d bounds;
  for (const auto& q : uv) bounds.extend(q);
  const Eigen::Vector2i bins = ((bounds.sizes() / kBin).array().floor().cast<int>() + 1).matrix();
  *count = 0;
  if (bins.x() > kMaxBins || bins.y() > kMaxBins) return bounds;
  std::vector<std::size_t> table((bins.x() + 1) * (bins.y() + 1), 0);
  const auto at = [&](int i, int j) -> std::size_t& { return table[j * (bins.x() + 1) + i]; };
  for (const auto& q : uv) {
    const Eigen::Vector2i b = ((q - bounds.min()) / kBin).array().floor().cast<int>();
    ++at(b.x() + 1, b.y() + 1);
  }
  for (int j = 1; j <= bins.y(); ++j)
    for (int i = 1; i <= bins.x(); ++i) at(i, j) += at(i - 1, j) + at(i, j - 1) - at(i - 1, j - 1);
  const int wu = std::min(bins.x(), static_cast<int>(std::ceil(size.x() / kBin)));
  const int wv = std::min(bins.y(), static_cast<int>(std::ceil(size.y() / kBin)));
  Eigen::Vector2i best(0, 0);
  for (int j = 0; j + wv <= bins.y(); ++j)
    for (int i = 0; i + wu <= bins.x(); ++i) {
      const std::size_t n = at(i + wu, j + wv) - at(i, j + wv) - at(i + wu, j) + at(i, j);
      if (n > *count) *count = n, best = Eigen::Vector2i(i, j);
    }
  const Eigen::Vector2d lo = bounds.min() + kBin * best.cast<double>();
  return Eigen::AlignedBox2d(lo, lo + kBin * Eigen::Vector2d(wu, wv));
}

std::uint64_t pack(std::int64_t u, std::int64_t v) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) |
         static_cast<std::uint32_t>(v);
}

Eigen::Vector2i unpack(std::uint64_t key) {
  return {static_cast<std::int32_t>(static_cast<std::uint32_t>(key >> 32)),
          static_cast<std::int32_t>(static_cast<std::uint32_t>(key & 0xFFFFFFFFu))};
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

PlaneGrid::PlaneGrid(const Plane& plane, const Eigen::Vector3d& axis, double gap_u, double gap_v)
    : axes_(plane_axes(plane.normal(), axis)),
      origin_(-plane.offset() * plane.normal()),
      inv_u_(1.0 / gap_u),
      inv_v_(1.0 / gap_v) {}

Eigen::Vector2d PlaneGrid::to_plane(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d q = p - origin_;
  return {q.dot(axes_.right), q.dot(axes_.up)};
}

Eigen::Vector2i PlaneGrid::index(const Eigen::Vector2d& uv) const {
  // Clamped so that a point kilometres away cannot overflow the int.
  constexpr double kLimit = 1e9;
  return {static_cast<int>(std::clamp(std::floor(uv.x() * inv_u_), -kLimit, kLimit)),
          static_cast<int>(std::clamp(std::floor(uv.y() * inv_v_), -kLimit, kLimit))};
}

std::uint64_t PlaneGrid::cell(const Eigen::Vector2d& uv) const {
  const Eigen::Vector2i c = index(uv);
  return pack(c.x(), c.y());
}

std::uint64_t PlaneGrid::neighbour(std::uint64_t cell, int du, int dv) const {
  const Eigen::Vector2i c = unpack(cell);
  return pack(static_cast<std::int64_t>(c.x()) + du, static_cast<std::int64_t>(c.y()) + dv);
}

PatchCells::PatchCells(const Eigen::AlignedBox2i& box_cells, const std::vector<Eigen::Vector2i>& cells) {
  // A bitmap up to this many cells: a board-sized box is a few hundred
  // cells, a wall's some ten thousand.
  constexpr std::int64_t kMaxDense = std::int64_t{1} << 22;
  if (box_cells.isEmpty()) return;
  const Eigen::Vector2i size = box_cells.sizes() + Eigen::Vector2i::Ones();
  const std::int64_t area = std::int64_t{size.x()} * size.y();
  if (area > kMaxDense) {
    for (const Eigen::Vector2i& c : cells)
      if (box_cells.contains(c)) sparse_.insert(pack(c.x(), c.y()));
    return;
  }
  origin_ = box_cells.min();
  columns_ = size.x();
  dense_.assign(static_cast<std::size_t>(area), 0);
  for (const Eigen::Vector2i& c : cells)
    if (box_cells.contains(c)) {
      const Eigen::Vector2i at = c - origin_;
      dense_[static_cast<std::size_t>(at.y()) * columns_ + at.x()] = 1;
    }
}

bool PatchCells::contains(const Eigen::Vector2i& cell) const {
  if (dense_.empty()) return sparse_.count(pack(cell.x(), cell.y())) > 0;
  const Eigen::Vector2i at = cell - origin_;
  return dense_[static_cast<std::size_t>(at.y()) * columns_ + at.x()] != 0;
}

bool in_patch(const PlaneGrid& grid, const Patch& patch, const Eigen::Vector2d& uv) {
  return patch.box.contains(uv) && patch.cells.contains(grid.index(uv));
}

bool in_patch(const PlaneGrid& grid, const Patch& patch, const Eigen::Vector3d& p) {
  return in_patch(grid, patch, grid.to_plane(p));
}

namespace {

/// The occupied cells of a plane grid and which cell each point is in.
struct Cells {
  std::vector<Eigen::Vector2d> uv;  // [m] each point in the plane
  std::vector<int> of_point;        // cell id of each point
  std::unordered_map<std::uint64_t, int> id;  // grid key -> cell id
  std::vector<std::uint64_t> keys;  // cell id -> grid key
  std::vector<int> count;           // points in each cell

  Cells(const PlaneGrid& grid, const std::vector<Eigen::Vector3d>& points)
      : uv(points.size()), of_point(points.size()) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      uv[i] = grid.to_plane(points[i]);
      const std::uint64_t key = grid.cell(uv[i]);
      const auto [it, inserted] = id.emplace(key, static_cast<int>(keys.size()));
      if (inserted) {
        keys.push_back(key);
        count.push_back(0);
      }
      of_point[i] = it->second;
      ++count[it->second];
    }
  }
};

/// Union-find parents joining 8-connected cells (a component's root is its
/// smallest cell id).
std::vector<int> connect(const PlaneGrid& grid, const Cells& cells) {
  std::vector<int> parent(cells.keys.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t c = 0; c < cells.keys.size(); ++c)
    for (int du = -1; du <= 1; ++du)
      for (int dv = -1; dv <= 1; ++dv) {
        const auto it = cells.id.find(grid.neighbour(cells.keys[c], du, dv));
        if (it == cells.id.end()) continue;
        const int a = find_root(parent, static_cast<int>(c));
        const int b = find_root(parent, it->second);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);  // smaller id wins: deterministic
      }
  return parent;
}

/// Fewest points a cell of component `best` needs to count towards the
/// patch's extent. Sparse cells hanging off the patch (the strip where the
/// board plane cuts the ground, a stand) would inflate it; the board's own
/// cells hold far more points than they do. The reference is the densest
/// tenth of the cells (a long stray strip can hold more cells than the
/// board, so the median is not safe).
double min_dense_cell_points(const Cells& cells, std::vector<int>& parent, int best) {
  std::vector<int> best_counts;
  for (std::size_t c = 0; c < cells.keys.size(); ++c)
    if (find_root(parent, static_cast<int>(c)) == best) best_counts.push_back(cells.count[c]);
  const std::size_t dense = best_counts.size() * 9 / 10;
  std::nth_element(best_counts.begin(), best_counts.begin() + dense, best_counts.end());
  return kSparseCellShare * best_counts[dense];
}

/// Cuts the patch to the best window when that holds window_share of its
/// members (then keeping only the members inside), and sets its box with a
/// margin of one bin (subsampling misses the extremes).
void fit_box(Patch& patch, std::vector<Eigen::Vector2d>& members, const Eigen::Vector2d& window,
             double window_share) {
  std::size_t in_window = 0;
  const Eigen::AlignedBox2d box = best_window(members, window, &in_window);
  patch.box = Eigen::AlignedBox2d();
  for (const auto& q : members) patch.box.extend(q);
  if (static_cast<double>(in_window) >= window_share * static_cast<double>(members.size())) {
    // Cut to the window, then shrink to the points inside it.
    std::vector<Eigen::Vector2d> inside;
    patch.box = Eigen::AlignedBox2d();
    for (const auto& q : members)
      if (box.contains(q)) inside.push_back(q), patch.box.extend(q);
    members.swap(inside);
    patch.points = members.size();
  }
  patch.box.extend(patch.box.min() - Eigen::Vector2d::Constant(kBin));
  patch.box.extend(patch.box.max() + Eigen::Vector2d::Constant(kBin));
}

/// Smallest-area enclosing rectangle over 1-degree steps: robust to a rolled board.
void fit_extent(Patch& patch, const std::vector<Eigen::Vector2d>& members) {
  double best_area = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kDirections; ++k) {
    const double angle = M_PI / 2.0 * k / kDirections;
    const Eigen::Vector2d a(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d b(-a.y(), a.x());
    double min_a = std::numeric_limits<double>::infinity(), max_a = -min_a, min_b = min_a, max_b = -min_a;
    for (const Eigen::Vector2d& q : members) {
      const double pa = q.dot(a), pb = q.dot(b);
      min_a = std::min(min_a, pa);
      max_a = std::max(max_a, pa);
      min_b = std::min(min_b, pb);
      max_b = std::max(max_b, pb);
    }
    const double wa = max_a - min_a, wb = max_b - min_b;
    if (wa * wb < best_area) {
      best_area = wa * wb;
      patch.extent_long = std::max(wa, wb);
      patch.extent_short = std::min(wa, wb);
    }
  }
}

}  // namespace

Patch largest_patch(const PlaneGrid& grid, const std::vector<Eigen::Vector3d>& points,
                    const Eigen::Vector2d& window, double window_share) {
  Patch patch;
  if (points.empty()) return patch;
  const Cells cells(grid, points);
  std::vector<int> parent = connect(grid, cells);
  std::vector<std::size_t> component_points(cells.keys.size(), 0);
  for (std::size_t c = 0; c < cells.keys.size(); ++c)
    component_points[find_root(parent, static_cast<int>(c))] += cells.count[c];
  const int best = static_cast<int>(std::max_element(component_points.begin(), component_points.end()) -
                                    component_points.begin());
  // Sparse cells stay in the patch (cells beside a hole are sparse too, and
  // their points are board points) but not in its extent.
  const double min_cell_points = min_dense_cell_points(cells, parent, best);
  std::vector<bool> dense_cell(cells.keys.size(), false);
  std::vector<Eigen::Vector2i> patch_cells;
  for (std::size_t c = 0; c < cells.keys.size(); ++c) {
    if (find_root(parent, static_cast<int>(c)) != best) continue;
    patch_cells.push_back(unpack(cells.keys[c]));
    dense_cell[c] = cells.count[c] >= min_cell_points;
  }
  patch.points = component_points[best];

  std::vector<Eigen::Vector2d> members;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (dense_cell[cells.of_point[i]]) members.push_back(cells.uv[i]);
  fit_box(patch, members, window, window_share);
  fit_extent(patch, members);
  Eigen::AlignedBox2i box_cells;
  if (!patch.box.isEmpty()) box_cells = Eigen::AlignedBox2i(grid.index(patch.box.min()), grid.index(patch.box.max()));
  patch.cells = PatchCells(box_cells, patch_cells);
  return patch;
}

}  // namespace l2s::detail
