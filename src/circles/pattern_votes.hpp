#pragma once
// The hole pattern found as a whole (private): a Hough transform over the
// pattern's placement in the board plane. Every edge point with a gradient
// votes for the two places one radius away along it (a rim's centre), and
// each such centre votes for the four placements of the pattern that would
// make it hole TL, TR, BL or BR; per in-plane angle the placements' votes
// pile up where all four holes agree. Single circles on clutter (the bricks
// seen through and around the holes, wood grain, a low-resolution rim) may
// outvote a true hole, but clutter rarely repeats the pattern's spacing.

#include "circles/circle_fit.hpp"

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace l2s::detail {

struct PatternVote {
  bool found = false;
  std::string reason;
  double angle = 0.0;                                // [rad] in [-pi/2, pi/2): labels nearest upright
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  // [m] pattern centre in the plane
  int support = 0;    // rim points of the weakest hole at the best placement
  int runner_up = 0;  // the same at the best placement elsewhere (centre more than one radius away)
};

/// The placement of `holes` (enum Hole order, board frame) with holes of
/// `radius` [m] whose weakest hole has the most rim points (within
/// `inlier_threshold` [m] of its rim, gradient along the radius), among the
/// placements that collect most votes. Not found when no point has a
/// direction, or when a placement elsewhere scores at least
/// `ambiguity_ratio` of the best (a repetitive texture). A placement is
/// judged by its weakest hole because a single strong circle of clutter
/// (a brick's arcs) adds many votes to every placement through it, while the
/// board is the one place where all four holes have rims.
PatternVote vote_hole_pattern(const std::vector<EdgePoint2>& points, const std::array<Eigen::Vector2d, 4>& holes,
                              double radius, double inlier_threshold, double ambiguity_ratio);

}  // namespace l2s::detail
