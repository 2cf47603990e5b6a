// Circle segmentation, paper Sec. III-C: edge points are brought into the
// board plane, circles of the known radius are found by sample consensus, and
// the known hole spacing selects the four that are the holes.
//
// Beyond the paper (Params::paper() switches it off): points are moved onto
// the plane along their own viewing ray, which removes range noise instead of
// keeping its in-plane part; the four holes are refit as one rigid pattern (3
// parameters from every edge point instead of 2 per hole from a few); and the
// board's thickness is modelled: seen obliquely, a hole's visible aperture is
// the intersection of its front and back rims (see circles/circle_fit.hpp).
#include <l2s/circle_finder.hpp>

#include <l2s/error.hpp>

#include "circles/circle_fit.hpp"
#include "circles/circle_votes.hpp"
#include "circles/hole_pattern.hpp"
#include "circles/pattern_votes.hpp"
#include "plane/plane_fit.hpp"

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace l2s {

namespace {

/// Edge points in the board plane's frame (x right, y up, z towards the
/// sensor), each with its aperture shift and in-plane gradient when known.
std::vector<detail::EdgePoint2> plane_points(const std::vector<Eigen::Vector3d>& edges,
                                             const std::vector<Eigen::Vector3d>& gradients, const Plane& plane,
                                             const detail::PlaneAxes& axes, const Eigen::Vector3d& origin,
                                             const Target& target, const CircleFinder::Params& params) {
  std::vector<detail::EdgePoint2> points;
  points.reserve(edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Eigen::Vector3d& q = edges[k];
    if (!q.allFinite() || q.norm() < 1e-9) continue;
    const Eigen::Vector3d ray = q.normalized();
    const double ray_normal = ray.dot(plane.normal());  // < 0: the ray goes away from the sensor side
    Eigen::Vector3d on_plane = q - plane.signedDistance(q) * plane.normal();
    if (params.project_along_rays && ray_normal < -1e-6) on_plane = ray * (-plane.offset() / ray_normal);
    detail::EdgePoint2 p;
    p.q = Eigen::Vector2d((on_plane - origin).dot(axes.right), (on_plane - origin).dot(axes.up));
    if (params.model_thickness && ray_normal < -1e-6) {
      const Eigen::Vector2d ray_inplane(ray.dot(axes.right), ray.dot(axes.up));
      p.shift = -target.board_thickness * ray_inplane / ray_normal;
    }
    if (!gradients.empty()) {
      const Eigen::Vector2d g(gradients[k].dot(axes.right), gradients[k].dot(axes.up));
      if (g.allFinite() && g.norm() > 1e-9) p.direction = g.normalized();
    }
    points.push_back(p);
  }
  return points;
}

/// The candidate search's settings for holes of `radius` [m].
detail::CandidateSearch candidate_search(const CircleFinder::Params& params, double radius) {
  detail::CandidateSearch search;
  search.radius = radius;
  search.inlier_threshold = params.inlier_threshold;
  search.min_points = static_cast<std::size_t>(params.min_circle_points);
  search.max_iterations = params.max_iterations;
  search.max_candidates = static_cast<std::size_t>(params.max_candidates);
  // Two candidates both within tolerance of one hole would make every frame ambiguous.
  search.separation = std::max(0.5 * radius, 2.0 * params.spacing_tolerance);
  return search;
}

/// The four holes refit as one rigid pattern from the matched one. Every
/// point within the threshold of a hole's aperture joins the fit, including
/// points the candidate search left to no circle. Returns the centres in the
/// plane frame; fills rms, radius, pattern_angle and fit_points.
std::array<Eigen::Vector2d, 4> fit_pattern(const std::vector<detail::EdgePoint2>& points,
                                           const detail::PatternMatch& match,
                                           const std::array<Eigen::Vector2d, 4>& holes, double radius,
                                           const CircleFinder::Params& params, CircleFinder::Result& result) {
  detail::PatternPose pose{match.offset, match.angle, radius};
  detail::RadiusFit radius_fit;
  radius_fit.free = params.fit_radius;
  radius_fit.nominal = radius;
  std::vector<int> hole_of(points.size(), -1);
  for (int pass = 0; pass < 2; ++pass) {
    result.fit_points = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      hole_of[i] = -1;
      double best = params.inlier_threshold;
      for (int h = 0; h < 4; ++h) {
        const double e = std::abs(detail::aperture_residual(points[i], pose.center(holes[h]), pose.radius));
        if (e <= best) best = e, hole_of[i] = h;
      }
      if (hole_of[i] >= 0) ++result.fit_points;
    }
    result.rms = detail::refine_pattern(points, hole_of, holes, radius_fit, params.max_refine_iterations, pose);
  }
  result.radius = pose.radius;
  result.pattern_angle = pose.angle;
  std::array<Eigen::Vector2d, 4> centers;
  for (int h = 0; h < 4; ++h) centers[h] = pose.center(holes[h]);
  return centers;
}

/// The paper's fit: each matched candidate refined on its own inliers.
/// Returns the centres in the plane frame; fills rms, radius, pattern_angle
/// and fit_points.
std::array<Eigen::Vector2d, 4> fit_each_circle(const std::vector<detail::EdgePoint2>& points,
                                               const std::vector<detail::CircleCandidate2>& candidates,
                                               const detail::PatternMatch& match, double radius,
                                               const CircleFinder::Params& params, CircleFinder::Result& result) {
  std::array<Eigen::Vector2d, 4> centers;
  double sum_sq = 0.0;
  result.fit_points = 0;
  for (int h = 0; h < 4; ++h) {
    const detail::CircleCandidate2& c = candidates[match.candidate_of_hole[h]];
    centers[h] = c.center;
    const double rms = detail::refine_circle(points, c.inliers, radius, params.max_refine_iterations, centers[h]);
    sum_sq += rms * rms * static_cast<double>(c.inliers.size());
    result.fit_points += c.inliers.size();
  }
  result.rms = result.fit_points ? std::sqrt(sum_sq / static_cast<double>(result.fit_points)) : 0.0;
  result.pattern_angle = match.angle;
  result.radius = radius;
  return centers;
}

/// The pattern found by its votes (see circles/pattern_votes.hpp), refit
/// jointly; false with a reason when the votes are ambiguous or a hole is
/// left with fewer than min_circle_points on its rim.
bool fit_voted_pattern(const std::vector<detail::EdgePoint2>& points, const std::array<Eigen::Vector2d, 4>& holes,
                       double radius, const CircleFinder::Params& params, std::array<Eigen::Vector2d, 4>& centers,
                       CircleFinder::Result& result) {
  const detail::PatternVote vote = detail::vote_hole_pattern(points, holes, radius, params.inlier_threshold, 0.8);
  if (!vote.found) {
    result.reason = "pattern votes: " + vote.reason;
    return false;
  }
  detail::PatternMatch match;
  match.found = true;
  match.offset = vote.offset;
  match.angle = vote.angle;
  centers = fit_pattern(points, match, holes, radius, params, result);
  for (int h = 0; h < 4; ++h) {
    int on_rim = 0;
    for (const detail::EdgePoint2& p : points)
      if (std::abs(detail::aperture_residual(p, centers[h], result.radius)) <= params.inlier_threshold) ++on_rim;
    if (on_rim < params.min_circle_points) {
      result.reason = std::string("pattern votes: hole ") + hole_name(static_cast<Hole>(h)) + " has " +
                      std::to_string(on_rim) + " rim point(s)";
      return false;
    }
  }
  return true;
}

}  // namespace

void CircleFinder::Params::validate() const {
  if (!(inlier_threshold > 0.0)) throw ParamError("inlier_threshold", "must be > 0 m");
  if (min_circle_points < 2) throw ParamError("min_circle_points", "must be >= 2");
  if (max_iterations < 1) throw ParamError("max_iterations", "must be >= 1");
  if (max_candidates < 4) throw ParamError("max_candidates", "must be >= 4");
  if (!(spacing_tolerance > 0.0)) throw ParamError("spacing_tolerance", "must be > 0 m");
  if (max_refine_iterations < 1) throw ParamError("max_refine_iterations", "must be >= 1");
}

CircleFinder::Params CircleFinder::Params::paper() {
  Params params;
  params.project_along_rays = false;
  params.joint_fit = false;
  params.model_thickness = false;
  params.fit_radius = false;
  params.pattern_votes = false;
  return params;
}

CircleFinder::CircleFinder() : CircleFinder(Params{}) {}

CircleFinder::CircleFinder(Params params) : params_(std::move(params)) { params_.validate(); }

CircleFinder::Result CircleFinder::find(const std::vector<Eigen::Vector3d>& edges, const Plane& plane_in,
                                        const Eigen::Vector3d& up, const Target& target,
                                        const std::vector<Eigen::Vector3d>& gradients) const {
  target.validate();
  if (!up.allFinite() || up.norm() < 1e-9) throw ParamError("up", "must be a finite non-zero vector");
  if (!gradients.empty() && gradients.size() != edges.size())
    throw ParamError("gradients", "must be empty or one per edge point");
  Result result;
  if (!plane_in.coeffs().allFinite() || plane_in.normal().norm() < 1e-9) {
    result.reason = "the plane is not finite";  // bad data, like too few edges: a reason, not an exception
    return result;
  }
  const Plane plane = detail::facing_origin(plane_in);
  const detail::PlaneAxes axes = detail::plane_axes(plane.normal(), up);
  const Eigen::Vector3d origin = -plane.offset() * plane.normal();
  const double radius = target.hole_radius;
  const std::vector<detail::EdgePoint2> points = plane_points(edges, gradients, plane, axes, origin, target, params_);
  const auto to_sensor = [&](const Eigen::Vector2d& c) -> Eigen::Vector3d {
    return origin + c.x() * axes.right + c.y() * axes.up;
  };

  const detail::CandidateSearch search = candidate_search(params_, radius);
  std::mt19937_64 rng(params_.seed);
  const std::vector<detail::CircleCandidate2> candidates =
      gradients.empty() ? detail::find_circle_candidates(points, search, rng)
                        : detail::find_circle_candidates_by_votes(points, search);
  std::vector<Eigen::Vector2d> candidate_centers;
  for (const detail::CircleCandidate2& c : candidates) {
    candidate_centers.push_back(c.center);
    result.candidates.push_back(Circle{to_sensor(c.center), plane.normal(), radius});
    result.candidate_points.push_back(c.inliers.size());
  }

  const std::array<Eigen::Vector2d, 4> holes = target.hole_centers();
  const detail::PatternMatch match = detail::match_hole_pattern(candidate_centers, result.candidate_points, holes,
                                                                params_.spacing_tolerance, radius);
  std::array<Eigen::Vector2d, 4> centers2;
  if (match.found) {
    result.matched = match.candidate_of_hole;
    centers2 = params_.joint_fit ? fit_pattern(points, match, holes, radius, params_, result)
                                 : fit_each_circle(points, candidates, match, radius, params_, result);
  } else {
    const bool votes = params_.pattern_votes && params_.joint_fit && !gradients.empty();
    if (!votes || !fit_voted_pattern(points, holes, radius, params_, centers2, result)) {
      result.reason = match.reason + (votes ? "; " + result.reason : "") + " (" + std::to_string(points.size()) +
                      " edge points)";
      return result;
    }
    result.reason.clear();
    result.by_pattern_votes = true;
  }
  for (int h = 0; h < 4; ++h) result.centers[h] = to_sensor(centers2[h]);
  result.found = true;
  return result;
}

}  // namespace l2s
