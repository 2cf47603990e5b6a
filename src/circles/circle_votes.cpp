#include "circles/circle_votes.hpp"

#include "circles/vote_grid.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace l2s::detail {

std::vector<CircleCandidate2> find_circle_candidates_by_votes(const std::vector<EdgePoint2>& points,
                                                              const CandidateSearch& search) {
  std::vector<CircleCandidate2> candidates;
  if (points.size() < 2 || !(search.radius > 0.0)) return candidates;
  const double r = search.radius;
  Eigen::AlignedBox2d box;
  for (const EdgePoint2& p : points)
    if (p.q.allFinite()) box.extend(p.q);
  if (box.isEmpty()) return candidates;
  VoteGrid votes(box, r, std::max(0.002, 0.25 * search.inlier_threshold));
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
