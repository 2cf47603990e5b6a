#pragma once
// Known-radius circle fitting in the board plane (private to the library).
//
// Every point carries an in-plane shift s: the ray through it crosses the back
// face of a board of thickness t at q + s, s = -t * d_inplane / d_normal. The
// ray passes the hole only if both q and q + s are inside the rim, so the
// visible aperture is the intersection of the circles (c, r) and (c - s, r) and
// a point on its outline has residual max(|q - c|, |q + s - c|) - r. A thin
// board is s = 0: the ordinary distance to the circle.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace l2s::detail {

struct EdgePoint2 {
  Eigen::Vector2d q;                             // [m] on the plane, (right, up)
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();  // [m] see above
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();  // unit intensity gradient in the plane, zero if unknown
};

/// Aperture residual of one point for a hole centred at c.
double aperture_residual(const EdgePoint2& p, const Eigen::Vector2d& c, double radius);

struct CircleCandidate2 {
  Eigen::Vector2d center;
  std::vector<std::size_t> inliers;
};

struct CandidateSearch {
  double radius = 0.12;
  double inlier_threshold = 0.02;
  std::size_t min_points = 3;
  int max_iterations = 2000;
  std::size_t max_candidates = 16;
  double separation = 0.06;  // candidates closer than this are the same circle
};

/// Circles of the known radius through pairs of points, scored by support,
/// best first and at least `separation` apart, each refit on its inliers.
std::vector<CircleCandidate2> find_circle_candidates(const std::vector<EdgePoint2>& points,
                                                     const CandidateSearch& search, std::mt19937_64& rng);

/// Gauss-Newton on one centre (radius fixed) over points[indices]; returns the rms.
double refine_circle(const std::vector<EdgePoint2>& points, const std::vector<std::size_t>& indices,
                     double radius, int iterations, Eigen::Vector2d& center);

/// A rigid placement of the hole pattern in the plane, c_h = R(angle) h + offset,
/// and the radius the holes appear to have.
struct PatternPose {
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  double angle = 0.0;   // [rad]
  double radius = 0.0;  // [m] apparent hole radius
  Eigen::Vector2d center(const Eigen::Vector2d& hole) const;
};

/// How refine_pattern treats the radius.
struct RadiusFit {
  bool free = false;         // estimate one apparent radius for all four holes
  double nominal = 0.12;     // [m] the target's radius: the prior, and the bounds' reference
  double prior_points = 2.0;  // the prior weighs as much as this many points saying "nominal"
};

/// Gauss-Newton on the pattern pose (and the common radius when free, the
/// spacing staying a hard constraint); hole_of[i] says which hole point i rims.
double refine_pattern(const std::vector<EdgePoint2>& points, const std::vector<int>& hole_of,
                      const std::array<Eigen::Vector2d, 4>& holes, const RadiusFit& radius_fit, int iterations,
                      PatternPose& pose);

}  // namespace l2s::detail
