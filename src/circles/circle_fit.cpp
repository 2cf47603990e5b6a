// Known-radius circles by sample consensus (paper Sec. III-C: "circles are
// segmented in the XY subspace through sample consensus, imposing the known
// circle radius") and the least-squares refinements used after it.
//
// With the radius known, two points fix a circle up to a mirror image, so
// hypotheses come from pairs: every pair when there are few (a lidar frame has
// tens of edge points, so the search is exhaustive and needs no luck), random
// seeded pairs otherwise.
#include "circles/circle_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

struct Hypothesis {
  Eigen::Vector2d center;
  std::size_t support;
  double cost;  // sum of squared residuals of the support
};

/// Jacobian of the aperture residual w.r.t. the centre, for the active branch.
Eigen::Vector2d residual_gradient(const EdgePoint2& p, const Eigen::Vector2d& c) {
  const Eigen::Vector2d front = p.q - c;
  const Eigen::Vector2d back = p.q + p.shift - c;
  const Eigen::Vector2d& e = back.norm() > front.norm() ? back : front;
  const double n = e.norm();
  return n > 1e-12 ? Eigen::Vector2d(-e / n) : Eigen::Vector2d::Zero();
}

}  // namespace

double aperture_residual(const EdgePoint2& p, const Eigen::Vector2d& c, double radius) {
  return std::max((p.q - c).norm(), (p.q + p.shift - c).norm()) - radius;
}

Eigen::Vector2d PatternPose::center(const Eigen::Vector2d& hole) const {
  return Eigen::Rotation2Dd(angle) * hole + offset;
}

std::vector<CircleCandidate2> find_circle_candidates(const std::vector<EdgePoint2>& points,
                                                     const CandidateSearch& search, std::mt19937_64& rng) {
  const std::size_t n = points.size();
  std::vector<CircleCandidate2> candidates;
  if (n < 2) return candidates;
  const double r = search.radius;
  const double max_chord = 2.0 * r + 2.0 * search.inlier_threshold;

  std::vector<Hypothesis> hypotheses;
  const auto add_pair = [&](std::size_t i, std::size_t j) {
    const Eigen::Vector2d a = points[i].q, b = points[j].q;
    const double chord = (b - a).norm();
    if (chord < 1e-6 || chord > max_chord) return;
    const Eigen::Vector2d mid = 0.5 * (a + b);
    const Eigen::Vector2d perp = Eigen::Vector2d(a.y() - b.y(), b.x() - a.x()) / chord;
    const double h = std::sqrt(std::max(0.0, r * r - 0.25 * chord * chord));
    for (double sign : {1.0, -1.0}) {
      Hypothesis hyp{mid + sign * h * perp, 0, 0.0};
      for (const EdgePoint2& p : points) {
        const double e = aperture_residual(p, hyp.center, r);
        if (std::abs(e) <= search.inlier_threshold) ++hyp.support, hyp.cost += e * e;
      }
      if (hyp.support >= search.min_points) hypotheses.push_back(hyp);
      if (h == 0.0) break;
    }
  };
  const std::size_t pairs = n * (n - 1) / 2;
  if (pairs <= static_cast<std::size_t>(search.max_iterations)) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) add_pair(i, j);
  } else {
    std::uniform_int_distribution<std::size_t> pick(0, n - 1);
    for (int k = 0; k < search.max_iterations; ++k) {
      const std::size_t i = pick(rng), j = pick(rng);
      if (i != j) add_pair(std::min(i, j), std::max(i, j));
    }
  }
  // Best support first, then lowest cost; stable keeps generation order on ties.
  std::stable_sort(hypotheses.begin(), hypotheses.end(), [](const Hypothesis& a, const Hypothesis& b) {
    return a.support != b.support ? a.support > b.support : a.cost < b.cost;
  });

  for (const Hypothesis& hyp : hypotheses) {
    if (candidates.size() >= search.max_candidates) break;
    const auto near = [&](const CircleCandidate2& c) { return (c.center - hyp.center).norm() < search.separation; };
    if (std::any_of(candidates.begin(), candidates.end(), near)) continue;
    CircleCandidate2 candidate{hyp.center, {}};
    for (int pass = 0; pass < 2; ++pass) {  // inliers, refit, inliers again
      candidate.inliers.clear();
      for (std::size_t i = 0; i < n; ++i)
        if (std::abs(aperture_residual(points[i], candidate.center, r)) <= search.inlier_threshold)
          candidate.inliers.push_back(i);
      if (pass == 0 && candidate.inliers.size() >= 3) refine_circle(points, candidate.inliers, r, 10, candidate.center);
    }
    if (candidate.inliers.size() < search.min_points) continue;
    // The refit may have slid onto an accepted circle.
    const auto same = [&](const CircleCandidate2& c) { return (c.center - candidate.center).norm() < search.separation; };
    if (std::any_of(candidates.begin(), candidates.end(), same)) continue;
    candidates.push_back(std::move(candidate));
  }
  return candidates;
}

double refine_circle(const std::vector<EdgePoint2>& points, const std::vector<std::size_t>& indices,
                     double radius, int iterations, Eigen::Vector2d& center) {
  if (indices.empty()) return 0.0;
  for (int it = 0; it < iterations; ++it) {
    Eigen::Matrix2d JtJ = Eigen::Matrix2d::Zero();
    Eigen::Vector2d Jtr = Eigen::Vector2d::Zero();
    for (std::size_t i : indices) {
      const Eigen::Vector2d J = residual_gradient(points[i], center);
      const double e = aperture_residual(points[i], center, radius);
      JtJ += J * J.transpose();
      Jtr += J * e;
    }
    // Points on one short arc leave the centre poorly constrained: damp a little.
    JtJ += 1e-9 * Eigen::Matrix2d::Identity();
    const Eigen::Vector2d step = -JtJ.ldlt().solve(Jtr);
    if (!step.allFinite()) break;
    center += step;
    if (step.norm() < 1e-10) break;
  }
  double sum_sq = 0.0;
  for (std::size_t i : indices) sum_sq += std::pow(aperture_residual(points[i], center, radius), 2);
  return std::sqrt(sum_sq / static_cast<double>(indices.size()));
}

double refine_pattern(const std::vector<EdgePoint2>& points, const std::vector<int>& hole_of,
                      const std::array<Eigen::Vector2d, 4>& holes, const RadiusFit& radius_fit, int iterations,
                      PatternPose& pose) {
  // Parameters: offset x, y, angle and (when free) radius. Real lidars see
  // holes smaller than they are (beam footprint, mixed returns); a fixed
  // radius then slides the centres towards the side with more rim points.
  const int n = radius_fit.free ? 4 : 3;
  for (int it = 0; it < iterations; ++it) {
    Eigen::Matrix4d JtJ = Eigen::Matrix4d::Zero();
    Eigen::Vector4d Jtr = Eigen::Vector4d::Zero();
    const Eigen::Rotation2Dd R(pose.angle);
    const Eigen::Matrix2d dR = (Eigen::Matrix2d() << -std::sin(pose.angle), -std::cos(pose.angle),
                                std::cos(pose.angle), -std::sin(pose.angle)).finished();
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (hole_of[i] < 0) continue;
      const Eigen::Vector2d& h = holes[hole_of[i]];
      const Eigen::Vector2d c = R * h + pose.offset;
      const Eigen::Vector2d g = residual_gradient(points[i], c);  // d residual / d centre
      const Eigen::Vector4d J(g.x(), g.y(), g.dot(dR * h), -1.0);
      const double e = aperture_residual(points[i], c, pose.radius);
      JtJ += J * J.transpose();
      Jtr += J * e;
    }
    if (radius_fit.free) {  // weak prior: holds the radius where the rims cannot tell it
      JtJ(3, 3) += radius_fit.prior_points;
      Jtr(3) += radius_fit.prior_points * (pose.radius - radius_fit.nominal);
    }
    const Eigen::MatrixXd A = JtJ.topLeftCorner(n, n) + 1e-9 * Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd step = -A.ldlt().solve(Jtr.head(n));
    if (!step.allFinite()) break;
    pose.offset += step.head<2>();
    pose.angle += step(2);
    if (radius_fit.free)
      pose.radius = std::clamp(pose.radius + step(3), 0.6 * radius_fit.nominal, 1.2 * radius_fit.nominal);
    if (step.norm() < 1e-10) break;
  }
  double sum_sq = 0.0;
  std::size_t used = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (hole_of[i] < 0) continue;
    sum_sq += std::pow(aperture_residual(points[i], pose.center(holes[hole_of[i]]), pose.radius), 2);
    ++used;
  }
  return used ? std::sqrt(sum_sq / static_cast<double>(used)) : 0.0;
}

}  // namespace l2s::detail
