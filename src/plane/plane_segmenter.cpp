// Board plane segmentation, paper Sec. III-B ("Target segmentation"): RANSAC
// with a tight threshold (delta_plane) for a plane parallel to the sensor's
// vertical axis within alpha_plane, then all points within delta_inliers.
//
// The paper keeps the single best plane; a wall behind the board is vertical
// and larger, so it would win. Here planes are extracted one after another and
// the first whose largest connected patch has the board's size is taken; every
// rejected candidate says why. The consensus is refit by least squares.
#include <l2s/plane_segmenter.hpp>

#include <l2s/error.hpp>

#include "plane/board_patch.hpp"
#include "plane/plane_fit.hpp"
#include "plane/vertical_plane_ransac.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>

namespace l2s {
namespace {

// A patch is cut to a board-sized window holding this share of it; less means
// a bigger surface (a wall) rather than the board with a thin line attached.
constexpr double kWindowShare = 0.9;

std::string format_size(double a, double b) {
  std::ostringstream out;
  out.precision(2);
  out << std::fixed << a << " x " << b << " m";
  return out.str();
}

/// Empty when the patch has the board's size, else why not.
std::string board_mismatch(const detail::Patch& patch, std::size_t patch_points, const Target& target,
                           const PlaneSegmenter::Params& params) {
  const double board_long = std::max(target.board_width, target.board_height);
  const double board_short = std::min(target.board_width, target.board_height);
  const double tol = params.size_tolerance;
  const std::string seen = "patch " + format_size(patch.extent_long, patch.extent_short) + ", board " +
                           format_size(board_long, board_short);
  if (patch_points < params.min_support) return "patch has too few points (" + std::to_string(patch_points) + ")";
  if (patch.extent_long > board_long * (1.0 + tol)) return "larger than the board (" + seen + ")";
  if (patch.extent_short > board_short * (1.0 + tol)) return "larger than the board (" + seen + ")";
  if (patch.extent_long < board_long * (1.0 - tol)) return "smaller than the board (" + seen + ")";
  // Lidar rings sample the height only at ring elevations: a loose lower bound.
  if (patch.extent_short < board_short * params.min_height_fraction)
    return "too thin for the board (" + seen + ")";
  return {};
}

}  // namespace

void PlaneSegmenter::Params::validate() const {
  const auto positive = [](double v, const char* field) {
    if (!(v > 0.0) || !std::isfinite(v)) throw ParamError(field, "must be a positive finite number");
  };
  positive(distance_threshold, "distance_threshold");
  positive(inlier_threshold, "inlier_threshold");
  positive(sample_radius, "sample_radius");
  positive(patch_gap_horizontal, "patch_gap_horizontal");
  positive(patch_gap_vertical, "patch_gap_vertical");
  if (!(max_angle >= 0.0 && max_angle <= M_PI / 2.0)) throw ParamError("max_angle", "must be in [0, pi/2] rad");
  if (!axis.allFinite() || axis.norm() < 1e-9) throw ParamError("axis", "must be a finite non-zero vector");
  if (max_iterations < 1) throw ParamError("max_iterations", "must be >= 1");
  if (max_candidates < 1) throw ParamError("max_candidates", "must be >= 1");
  if (min_support < 3) throw ParamError("min_support", "must be >= 3");
  if (max_samples < 100) throw ParamError("max_samples", "must be >= 100");
  if (!(size_tolerance >= 0.0 && size_tolerance < 1.0)) throw ParamError("size_tolerance", "must be in [0, 1)");
  if (!(min_height_fraction >= 0.0 && min_height_fraction <= 1.0))
    throw ParamError("min_height_fraction", "must be in [0, 1]");
}

PlaneSegmenter::Params PlaneSegmenter::Params::lidar() { return Params{}; }

PlaneSegmenter::Params PlaneSegmenter::Params::stereo() {
  Params params;
  params.inlier_threshold = 0.10;
  params.axis = -Eigen::Vector3d::UnitY();  // optical frame: y points down
  params.patch_gap_horizontal = 0.1;        // dense cloud: holes need not be bridged by one ring
  params.patch_gap_vertical = 0.1;
  return params;
}

PlaneSegmenter::PlaneSegmenter() : PlaneSegmenter(Params{}) {}

PlaneSegmenter::PlaneSegmenter(Params params) : params_(std::move(params)) {
  params_.validate();
  params_.axis.normalize();
}

PlaneSegmenter::Result PlaneSegmenter::segment(const std::vector<Eigen::Vector3d>& points,
                                               const Target& target) const {
  target.validate();
  Result result;
  std::vector<std::size_t> finite;
  finite.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].allFinite()) finite.push_back(i);
  if (finite.size() < params_.min_support) {
    result.reason = "only " + std::to_string(finite.size()) + " finite points";
    return result;
  }

  // A random subset in random order: RANSAC pre-scores on its prefix.
  std::mt19937_64 rng(params_.seed);
  const std::size_t sample_count = std::min(finite.size(), params_.max_samples);
  for (std::size_t i = 0; i < sample_count; ++i) {
    std::uniform_int_distribution<std::size_t> pick(i, finite.size() - 1);
    std::swap(finite[i], finite[pick(rng)]);
  }
  std::vector<Eigen::Vector3d> samples(sample_count);
  for (std::size_t i = 0; i < sample_count; ++i) samples[i] = points[finite[i]];

  detail::VerticalPlaneRansacParams ransac;
  ransac.distance_threshold = params_.distance_threshold;
  ransac.max_sin_axis = std::sin(params_.max_angle);
  ransac.axis = params_.axis;
  ransac.max_iterations = params_.max_iterations;
  ransac.sample_radius = params_.sample_radius;

  for (int c = 0; c < params_.max_candidates && samples.size() >= 3; ++c) {
    const detail::VerticalPlaneRansacResult found = detail::find_vertical_plane(samples, ransac, rng);
    if (!found.found) break;

    // Refit on the sample consensus; keep the hypothesis if the refit leaves the cone.
    std::vector<std::size_t> consensus;
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (std::abs(found.plane.signedDistance(samples[i])) <= params_.distance_threshold) consensus.push_back(i);
    Plane plane = detail::fit_plane(samples, consensus);
    if (std::abs(plane.normal().dot(params_.axis)) > ransac.max_sin_axis) plane = found.plane;
    plane = detail::facing_origin(plane);

    std::vector<Eigen::Vector3d> on_plane;
    for (const Eigen::Vector3d& p : samples)
      if (std::abs(plane.signedDistance(p)) <= params_.distance_threshold) on_plane.push_back(p);
    const detail::PlaneGrid grid(plane, params_.axis, params_.patch_gap_horizontal, params_.patch_gap_vertical);
    // The window allows the board's size plus tolerance, horizontally long.
    const double tol = 1.0 + params_.size_tolerance;
    const Eigen::Vector2d window(tol * std::max(target.board_width, target.board_height),
                                 tol * std::min(target.board_width, target.board_height));
    const detail::Patch patch = detail::largest_patch(grid, on_plane, window, kWindowShare);
    // Patch membership of a point never changes for this candidate, but the
    // refit passes below ask again; a dense stereo cloud makes that the
    // segmenter's hot spot, so each point is looked up once.
    std::vector<signed char> membership(points.size(), -1);
    const auto in_patch = [&](std::size_t i) {
      if (membership[i] < 0) membership[i] = detail::in_patch(grid, patch, points[i]) ? 1 : 0;
      return membership[i] == 1;
    };

    // One pass over the full cloud: support, and the consensus inside the patch.
    PlaneCandidate candidate;
    candidate.plane = plane;
    candidate.extent_long = patch.extent_long;
    candidate.extent_short = patch.extent_short;
    std::vector<std::size_t> patch_consensus;
    for (std::size_t i : finite) {
      if (std::abs(plane.signedDistance(points[i])) > params_.distance_threshold) continue;
      ++candidate.support;
      if (in_patch(i)) patch_consensus.push_back(i);
    }
    candidate.patch_points = patch_consensus.size();
    if (candidate.support < params_.min_support) {
      candidate.reason = "support " + std::to_string(candidate.support) + " below min_support";
      result.candidates.push_back(candidate);
      break;  // candidates come in decreasing support: none left can be the board
    }
    candidate.reason = board_mismatch(patch, candidate.patch_points, target, params_);
    if (!candidate.reason.empty()) {
      result.candidates.push_back(candidate);
      // Drop this patch (thick surfaces too: inlier_threshold) and look again.
      std::vector<Eigen::Vector3d> rest;
      rest.reserve(samples.size());
      for (const Eigen::Vector3d& p : samples)
        if (std::abs(plane.signedDistance(p)) > params_.inlier_threshold || !detail::in_patch(grid, patch, p))
          rest.push_back(p);
      if (rest.size() == samples.size()) break;
      samples.swap(rest);
      continue;
    }

    // The board: least-squares refit on its full-cloud consensus, then again on
    // everything within delta_inliers (a thin consensus slice of a noisy stereo
    // cloud leans towards the hypothesis it was cut with).
    Plane refit = detail::facing_origin(detail::fit_plane(points, patch_consensus));
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::size_t> wide;
      for (std::size_t i : finite)
        if (std::abs(refit.signedDistance(points[i])) <= params_.inlier_threshold && in_patch(i))
          wide.push_back(i);
      if (wide.size() < 3) break;
      refit = detail::facing_origin(detail::fit_plane(points, wide));
    }
    double sum_sq = 0.0;
    for (std::size_t i : patch_consensus) sum_sq += std::pow(refit.signedDistance(points[i]), 2);
    candidate.plane = refit;
    candidate.accepted = true;
    result.candidates.push_back(candidate);
    result.plane = refit;
    result.rms = std::sqrt(sum_sq / static_cast<double>(patch_consensus.size()));
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].allFinite() && std::abs(refit.signedDistance(points[i])) <= params_.inlier_threshold &&
          in_patch(i))
        result.inliers.push_back(i);
    result.found = true;
    return result;
  }
  std::ostringstream reason;
  reason << "no board-sized plane among " << result.candidates.size() << " candidate(s)";
  for (std::size_t i = 0; i < result.candidates.size(); ++i)
    reason << (i ? "; " : ": ") << "#" << i << " " << result.candidates[i].reason;
  result.reason = reason.str();
  return result;
}

}  // namespace l2s
