#include "circles/pattern_votes.hpp"

#include "circles/vote_grid.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace l2s::detail {
namespace {

constexpr std::size_t kPeaksPerAngle = 3;
constexpr double kMaxCells = 6.0e4;  // ~2.4 x 2.4 m at 1 cm
constexpr std::size_t kPlacementsJudged = 40;  // the most voted placements, judged by their weakest hole
constexpr double kMinRadialCos = 0.7;          // a rim point's gradient within ~45 deg of its radius

struct Placement {
  float votes = 0.0f;
  double angle = 0.0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
};

/// The centres the rims vote for: one radius along each gradient, both ways
/// (a hole may be darker or brighter than the board).
std::vector<Eigen::Vector2d> rim_centres(const std::vector<EdgePoint2>& points, double radius) {
  std::vector<Eigen::Vector2d> centres;
  for (const EdgePoint2& p : points) {
    if (p.direction.squaredNorm() < 0.5 || !p.q.allFinite()) continue;
    centres.push_back(p.q + radius * p.direction);
    centres.push_back(p.q - radius * p.direction);
  }
  return centres;
}

/// Rim points of the weakest hole of the pattern placed at (angle, offset).
int weakest_hole_support(const std::vector<EdgePoint2>& points, const std::array<Eigen::Vector2d, 4>& holes,
                         double radius, double inlier_threshold, const Placement& placement) {
  const Eigen::Rotation2Dd R(placement.angle);
  int weakest = std::numeric_limits<int>::max();
  for (const Eigen::Vector2d& h : holes) {
    const Eigen::Vector2d c = R * h + placement.offset;
    int support = 0;
    for (const EdgePoint2& p : points) {
      if (std::abs(aperture_residual(p, c, radius)) > inlier_threshold) continue;
      const Eigen::Vector2d out = p.q - c;
      const bool radial = p.direction.squaredNorm() < 0.5 || std::abs(p.direction.dot(out)) >= kMinRadialCos * out.norm();
      if (radial) ++support;
    }
    weakest = std::min(weakest, support);
  }
  return weakest;
}

/// The strongest few placements at each in-plane angle, from the votes.
std::vector<Placement> voted_placements(const std::vector<Eigen::Vector2d>& centres,
                                        const std::array<Eigen::Vector2d, 4>& holes, double cell) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& c : centres) box.extend(c);
  double reach = 0.0;  // [m] farthest hole from the pattern centre
  for (const Eigen::Vector2d& h : holes) reach = std::max(reach, h.norm());
  // The grid is cleared, smoothed and searched once per angle: a wide spread
  // of edges (a wall taken for the board) coarsens its cells instead.
  VoteGrid grid(box, reach, cell, kMaxCells);
  // An angle step that moves the farthest hole by about one cell; the
  // pattern is symmetric under a half turn, so half a turn covers every roll.
  const int steps = std::max(8, static_cast<int>(std::ceil(M_PI * reach / grid.cell())));
  std::vector<Placement> tops;
  for (int k = 0; k < steps; ++k) {
    const double angle = -0.5 * M_PI + M_PI * k / steps;
    const Eigen::Rotation2Dd R(angle);
    std::array<Eigen::Vector2d, 4> rotated;
    for (int h = 0; h < 4; ++h) rotated[h] = R * holes[h];
    grid.clear();
    for (const Eigen::Vector2d& c : centres)
      for (const Eigen::Vector2d& h : rotated) grid.vote(c - h);
    grid.smooth();
    const auto peaks = grid.peaks(kPeaksPerAngle);
    for (std::size_t i = 0; i < peaks.size() && i < kPeaksPerAngle; ++i) tops.push_back({peaks[i].first, angle, peaks[i].second});
  }
  std::sort(tops.begin(), tops.end(), [](const Placement& a, const Placement& b) { return a.votes > b.votes; });
  if (tops.size() > kPlacementsJudged) tops.resize(kPlacementsJudged);
  return tops;
}

}  // namespace

PatternVote vote_hole_pattern(const std::vector<EdgePoint2>& points, const std::array<Eigen::Vector2d, 4>& holes,
                              double radius, double inlier_threshold, double ambiguity_ratio) {
  PatternVote result;
  const std::vector<Eigen::Vector2d> centres = rim_centres(points, radius);
  if (centres.empty()) {
    result.reason = "no edge point has a gradient direction";
    return result;
  }
  // Half the inlier threshold: the joint refit pulls the placement the rest of the way.
  std::vector<Placement> placements = voted_placements(centres, holes, 0.5 * inlier_threshold);
  std::vector<int> support;
  for (const Placement& p : placements) support.push_back(weakest_hole_support(points, holes, radius, inlier_threshold, p));
  const auto best = std::max_element(support.begin(), support.end());
  if (best == support.end() || *best <= 0) {
    result.reason = "no placement has rim points at all four holes";
    return result;
  }
  const Placement& chosen = placements[static_cast<std::size_t>(best - support.begin())];
  result.angle = chosen.angle;
  result.offset = chosen.offset;
  result.support = *best;
  for (std::size_t i = 0; i < placements.size(); ++i)
    if ((placements[i].offset - chosen.offset).norm() > radius) result.runner_up = std::max(result.runner_up, support[i]);
  if (result.runner_up >= ambiguity_ratio * result.support) {
    std::ostringstream reason;
    reason << "two placements of the pattern are as well supported (weakest hole " << result.runner_up << " vs "
           << result.support << " rim points)";
    result.reason = reason.str();
    return result;
  }
  result.found = true;
  return result;
}

}  // namespace l2s::detail
