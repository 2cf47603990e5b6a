#pragma once
// Known-radius circle candidates from edge directions (private): a circular
// Hough transform with gradients (Ballard 1981; Kimme et al. 1975). An image
// edge on a hole's rim has its intensity gradient along the radius, so each
// edge point votes for the two places one radius away along its gradient;
// the votes of a rim pile up at its centre. A textured board (wood grain)
// adds many edges, but their gradients do not point at common centres.

#include "circles/circle_fit.hpp"

#include <vector>

namespace l2s::detail {

/// Candidates from the votes of points with a direction (points without one
/// do not vote, but count as inliers), best supported first, each refit on its
/// inliers; `search` as for find_circle_candidates.
std::vector<CircleCandidate2> find_circle_candidates_by_votes(const std::vector<EdgePoint2>& points,
                                                              const CandidateSearch& search);

}  // namespace l2s::detail
