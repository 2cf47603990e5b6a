#include "circles/vote_grid.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {

VoteGrid::VoteGrid(const Eigen::AlignedBox2d& box, double margin, double cell, double max_cells) {
  if (box.isEmpty()) return;
  const Eigen::Vector2d span = box.sizes() + Eigen::Vector2d::Constant(2.0 * margin);
  cell = std::max(cell, std::sqrt(span.x() * span.y() / max_cells));
  cell_ = cell;
  origin_ = box.min() - Eigen::Vector2d::Constant(margin + 2.0 * cell);
  width_ = static_cast<int>(std::ceil(span.x() / cell)) + 5;
  height_ = static_cast<int>(std::ceil(span.y() / cell)) + 5;
  votes_.assign(static_cast<std::size_t>(width_) * height_, 0.0f);
}

void VoteGrid::clear() { std::fill(votes_.begin(), votes_.end(), 0.0f); }

void VoteGrid::vote(const Eigen::Vector2d& c, float weight) {
  const Eigen::Vector2d g = (c - origin_) / cell_ - Eigen::Vector2d::Constant(0.5);
  const int x = static_cast<int>(std::floor(g.x())), y = static_cast<int>(std::floor(g.y()));
  if (x < 0 || y < 0 || x + 1 >= width_ || y + 1 >= height_) return;
  const float fx = static_cast<float>(g.x() - x), fy = static_cast<float>(g.y() - y);
  at(x, y) += weight * (1 - fx) * (1 - fy);
  at(x + 1, y) += weight * fx * (1 - fy);
  at(x, y + 1) += weight * (1 - fx) * fy;
  at(x + 1, y + 1) += weight * fx * fy;
}

void VoteGrid::smooth() {
  scratch_.assign(votes_.size(), 0.0f);
  for (int y = 1; y + 1 < height_; ++y)
    for (int x = 1; x + 1 < width_; ++x) {
      float sum = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) sum += at(x + dx, y + dy);
      scratch_[index(x, y)] = sum;
    }
  votes_.swap(scratch_);
}

std::vector<std::pair<float, Eigen::Vector2d>> VoteGrid::peaks(std::size_t max_peaks) const {
  if (max_peaks == 0) return {};
  std::vector<std::pair<float, std::size_t>> found;  // (votes, cell index)
  // Once `max_peaks` maxima are kept, a cell must beat the weakest of them to
  // matter (cells are scanned in order, so a tie loses to the earlier one):
  // most cells then cost one comparison instead of eight, and the pattern
  // search reads its grid once per angle.
  float floor = 0.0f;
  std::size_t weakest = 0;
  for (int y = 1; y + 1 < height_; ++y)
    for (int x = 1; x + 1 < width_; ++x) {
      const float v = votes_[index(x, y)];
      if (v <= floor) continue;
      bool peak = true;
      for (int dy = -1; dy <= 1 && peak; ++dy)
        for (int dx = -1; dx <= 1 && peak; ++dx)
          if ((dx || dy) && (votes_[index(x + dx, y + dy)] > v || (votes_[index(x + dx, y + dy)] == v && dy * 3 + dx < 0)))
            peak = false;
      if (!peak) continue;
      if (found.size() < max_peaks) {
        found.emplace_back(v, index(x, y));
        if (found.size() < max_peaks) continue;
      } else {
        found[weakest] = {v, index(x, y)};
      }
      // The weakest kept: fewest votes, and of equal ones the latest cell.
      weakest = 0;
      for (std::size_t i = 1; i < found.size(); ++i)
        if (found[i].first < found[weakest].first ||
            (found[i].first == found[weakest].first && found[i].second > found[weakest].second))
          weakest = i;
      floor = found[weakest].first;
    }
  const auto stronger = [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); };
  const std::size_t kept = std::min(max_peaks, found.size());
  std::partial_sort(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(kept), found.end(), stronger);
  std::vector<std::pair<float, Eigen::Vector2d>> out;
  out.reserve(kept);
  for (std::size_t i = 0; i < kept; ++i) {
    const auto [v, cell] = found[i];
    const int x = static_cast<int>(cell % static_cast<std::size_t>(width_)), y = static_cast<int>(cell / static_cast<std::size_t>(width_));
    out.emplace_back(v, origin_ + cell_ * Eigen::Vector2d(x + 0.5, y + 0.5));
  }
  return out;
}

}  // namespace l2s::detail
