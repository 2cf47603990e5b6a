#include "circles/circle_votes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

/// A 2D vote accumulator over the points' bounding box widened by a radius.
class Accumulator {
 public:
  /// The cell grows when the points spread wide (a candidate plane may be a whole wall): the grid
  /// never holds more than kMaxCells, whatever the input.
  Accumulator(const std::vector<EdgePoint2>& points, double radius, double cell) {
    Eigen::AlignedBox2d box;
    for (const EdgePoint2& p : points)
      if (p.q.allFinite()) box.extend(p.q);
    if (box.isEmpty()) return;
    const Eigen::Vector2d span = box.sizes() + Eigen::Vector2d::Constant(2.0 * radius);
    cell = std::max(cell, std::sqrt(span.x() * span.y() / kMaxCells));
    cell_ = cell;
    origin_ = box.min() - Eigen::Vector2d::Constant(radius + 2.0 * cell);
    width_ = static_cast<int>(std::ceil(span.x() / cell)) + 5;
    height_ = static_cast<int>(std::ceil(span.y() / cell)) + 5;
    votes_.assign(static_cast<std::size_t>(width_) * height_, 0.0f);
  }

  /// Bilinear splat, so a peak's position keeps sub-cell precision.
  void vote(const Eigen::Vector2d& c) {
    const Eigen::Vector2d g = (c - origin_) / cell_ - Eigen::Vector2d::Constant(0.5);
    const int x = static_cast<int>(std::floor(g.x())), y = static_cast<int>(std::floor(g.y()));
    if (x < 0 || y < 0 || x + 1 >= width_ || y + 1 >= height_) return;
    const float fx = static_cast<float>(g.x() - x), fy = static_cast<float>(g.y() - y);
    at(x, y) += (1 - fx) * (1 - fy);
    at(x + 1, y) += fx * (1 - fy);
    at(x, y + 1) += (1 - fx) * fy;
    at(x + 1, y + 1) += fx * fy;
  }

  /// 3x3 box sum: a rim's votes spread over neighbouring cells with noise.
  void smooth() {
    std::vector<float> out(votes_.size(), 0.0f);
    for (int y = 1; y + 1 < height_; ++y)
      for (int x = 1; x + 1 < width_; ++x) {
        float sum = 0.0f;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) sum += at(x + dx, y + dy);
        out[index(x, y)] = sum;
      }
    votes_.swap(out);
  }

  /// Local maxima (strict over the 8 neighbours), strongest first.
  std::vector<std::pair<float, Eigen::Vector2d>> peaks() const {
    std::vector<std::pair<float, Eigen::Vector2d>> out;
    for (int y = 1; y + 1 < height_; ++y)
      for (int x = 1; x + 1 < width_; ++x) {
        const float v = votes_[index(x, y)];
        if (v <= 0.0f) continue;
        bool peak = true;
        for (int dy = -1; dy <= 1 && peak; ++dy)
          for (int dx = -1; dx <= 1 && peak; ++dx)
            if ((dx || dy) && (votes_[index(x + dx, y + dy)] > v || (votes_[index(x + dx, y + dy)] == v && dy * 3 + dx < 0)))
              peak = false;
        if (peak) out.emplace_back(v, origin_ + cell_ * Eigen::Vector2d(x + 0.5, y + 0.5));
      }
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    return out;
  }

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  float& at(int x, int y) { return votes_[index(x, y)]; }
  float at(int x, int y) const { return votes_[index(x, y)]; }

  static constexpr double kMaxCells = 4.0e6;
  double cell_ = 0.0;
  Eigen::Vector2d origin_;
  int width_ = 0, height_ = 0;
  std::vector<float> votes_;
};

}  // namespace

std::vector<CircleCandidate2> find_circle_candidates_by_votes(const std::vector<EdgePoint2>& points,
                                                              const CandidateSearch& search) {
  std::vector<CircleCandidate2> candidates;
  if (points.size() < 2 || !(search.radius > 0.0)) return candidates;
  const double r = search.radius;
  Accumulator votes(points, r, std::max(0.002, 0.25 * search.inlier_threshold));
  for (const EdgePoint2& p : points) {
    if (p.direction.squaredNorm() < 0.5 || !p.q.allFinite()) continue;
    votes.vote(p.q + r * p.direction);  // the hole may be darker or brighter than the board
    votes.vote(p.q - r * p.direction);
  }
  votes.smooth();
  for (const auto& peak : votes.peaks()) {
    const Eigen::Vector2d centre = peak.second;  // a named copy: lambdas may not capture structured bindings (C++17)
    if (candidates.size() >= search.max_candidates) break;
    const auto near = [&](const CircleCandidate2& c) { return (c.center - centre).norm() < search.separation; };
    if (std::any_of(candidates.begin(), candidates.end(), near)) continue;
    CircleCandidate2 candidate{centre, {}};
    for (int pass = 0; pass < 2; ++pass) {  // inliers, refit, inliers again
      candidate.inliers.clear();
      for (std::size_t i = 0; i < points.size(); ++i)
        if (std::abs(aperture_residual(points[i], candidate.center, r)) <= search.inlier_threshold)
          candidate.inliers.push_back(i);
      if (pass == 0 && candidate.inliers.size() >= 3) refine_circle(points, candidate.inliers, r, 10, candidate.center);
    }
    if (candidate.inliers.size() < search.min_points) continue;
    if (std::any_of(candidates.begin(), candidates.end(), [&](const CircleCandidate2& c) {
          return (c.center - candidate.center).norm() < search.separation;
        }))
      continue;
    candidates.push_back(std::move(candidate));
  }
  return candidates;
}

}  // namespace l2s::detail
