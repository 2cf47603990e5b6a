// Board plane segmentation, paper Sec. III-B ("Target segmentation"): RANSAC
// with a tight threshold (delta_plane) for a plane parallel to the sensor's
// vertical axis within alpha_plane, then all points within delta_inliers.
//
// The paper keeps the single best plane; a wall behind the board is vertical
// and larger, so it would win. Here planes are extracted one after another,
// each cut to its largest connected patch. Every board-sized patch is a
// hypothesis (the branches verify each by its holes); they are ranked by how
// board-like they are: the size, and whether the surface stands apart (a
// window cut out of a side wall has coplanar points all around it, a board
// has none). Every rejected candidate says why. Plausible candidates are
// refit by least squares.
#include <l2s/plane_segmenter.hpp>

#include <l2s/error.hpp>

#include "plane/board_patch.hpp"
#include "plane/plane_fit.hpp"
#include "plane/vertical_plane_ransac.hpp"

#include <algorithm>
#include <array>
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
constexpr const char* kLargerThanTheBoard = "larger than the board";

std::string board_mismatch(const detail::Patch& patch, std::size_t patch_points, const Target& target,
                           const PlaneSegmenter::Params& params) {
  const double board_long = std::max(target.board_width, target.board_height);
  const double board_short = std::min(target.board_width, target.board_height);
  const double tol = params.size_tolerance;
  const std::string seen = "patch " + format_size(patch.extent_long, patch.extent_short) + ", board " +
                           format_size(board_long, board_short);
  if (patch_points < params.min_support) return "patch has too few points (" + std::to_string(patch_points) + ")";
  if (patch.extent_long > board_long * (1.0 + tol)) return kLargerThanTheBoard + (" (" + seen + ")");
  if (patch.extent_short > board_short * (1.0 + tol)) return kLargerThanTheBoard + (" (" + seen + ")");
  if (patch.extent_long < board_long * params.min_length_fraction) return "smaller than the board (" + seen + ")";
  // Lidar rings sample the height only at ring elevations: a loose lower bound.
  if (patch.extent_short < board_short * params.min_height_fraction)
    return "too thin for the board (" + seen + ")";
  return {};
}


/// Coplanar density in four bands (left, right, below, above) around the
/// patch box, relative to the density inside it; the second highest side. A
/// board touches at most one other surface (the ground or its stand below),
/// a window of a wall continues on at least two sides.
class IsolationCounter {
 public:
  IsolationCounter(const Eigen::AlignedBox2d& box, double band) : box_(box), band_(band) {}

  void add(const Eigen::Vector2d& uv) {
    if (box_.contains(uv)) {
      ++inside_;
      return;
    }
    const Eigen::Vector2d lo = box_.min(), hi = box_.max();
    const bool rows = uv.y() >= lo.y() && uv.y() <= hi.y(), cols = uv.x() >= lo.x() && uv.x() <= hi.x();
    if (rows && uv.x() < lo.x() && uv.x() >= lo.x() - band_) ++side_[0];
    if (rows && uv.x() > hi.x() && uv.x() <= hi.x() + band_) ++side_[1];
    if (cols && uv.y() < lo.y() && uv.y() >= lo.y() - band_) ++side_[2];
    if (cols && uv.y() > hi.y() && uv.y() <= hi.y() + band_) ++side_[3];
  }

  double isolation() const {
    const Eigen::Vector2d size = box_.sizes();
    if (inside_ == 0 || size.prod() <= 0.0) return 0.0;
    const double density = static_cast<double>(inside_) / size.prod();
    std::array<double, 4> ratio{};
    for (int k = 0; k < 4; ++k) {
      const double area = band_ * (k < 2 ? size.y() : size.x());
      ratio[k] = std::min(1.0, static_cast<double>(side_[k]) / area / density);
    }
    std::sort(ratio.begin(), ratio.end());
    return ratio[2];
  }

 private:
  Eigen::AlignedBox2d box_;
  double band_;
  std::size_t inside_ = 0;
  std::array<std::size_t, 4> side_{};
};

/// Board-likeness 0..1: the length match, how much of the board's height the
/// patch covers (a strip of a wall is as long as the board but thin), and the
/// isolation.
double board_prior(const PlaneCandidate& c, const Target& target, double size_tolerance) {
  const double board_long = std::max(target.board_width, target.board_height);
  const double board_short = std::min(target.board_width, target.board_height);
  const double size_error = std::abs(c.extent_long / board_long - 1.0) / std::max(size_tolerance, 1e-6);
  const double height = std::min(1.0, c.extent_short / board_short);
  return (1.0 - 0.5 * std::min(1.0, size_error)) * (0.5 + 0.5 * height) * (1.0 - 0.9 * c.isolation);
}

/// The distances that count as "on the plane", per point: fixed, or growing
/// with the depth noise of a stereo cloud.
struct Thresholds {
  double distance, inlier, noise;
  explicit Thresholds(const PlaneSegmenter::Params& p)
      : distance(p.distance_threshold), inlier(p.inlier_threshold), noise(p.depth_noise) {}
  double consensus(const Eigen::Vector3d& p) const { return std::max(distance, 2.0 * noise * p.squaredNorm()); }
  double inliers(const Eigen::Vector3d& p) const { return std::max(inlier, 3.0 * noise * p.squaredNorm()); }
};

struct Samples {
  std::vector<std::size_t> finite;      // indices of the finite input points, in order
  std::vector<Eigen::Vector3d> points;  // random subset in random order (RANSAC pre-scores a prefix)
  std::vector<double> tolerance;        // consensus distance of each sample
};

Samples draw_samples(const std::vector<Eigen::Vector3d>& points, std::size_t max_samples, const Thresholds& t,
                     std::mt19937_64& rng) {
  Samples s;
  s.finite.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].allFinite()) s.finite.push_back(i);
  // Drawn by a partial shuffle of a copy: the passes over the full cloud go
  // through `finite` in memory order (in shuffled order, each of a dense
  // cloud's points was a cache miss: 40 % of the segmenter's time).
  std::vector<std::size_t> order = s.finite;
  const std::size_t count = std::min(order.size(), max_samples);
  for (std::size_t i = 0; i < count; ++i) {
    std::uniform_int_distribution<std::size_t> pick(i, order.size() - 1);
    std::swap(order[i], order[pick(rng)]);
  }
  s.points.resize(count);
  s.tolerance.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    s.points[i] = points[order[i]];
    s.tolerance[i] = t.consensus(s.points[i]);
  }
  return s;
}

/// The RANSAC hypothesis refit on its sample consensus, unless the refit leaves the cone.
Plane refit_hypothesis(const Plane& hypothesis, const Samples& samples, const PlaneSegmenter::Params& params,
                       double max_sin_axis) {
  std::vector<std::size_t> consensus;
  for (std::size_t i = 0; i < samples.points.size(); ++i)
    if (std::abs(hypothesis.signedDistance(samples.points[i])) <= samples.tolerance[i]) consensus.push_back(i);
  Plane plane = detail::fit_plane(samples.points, consensus);
  if (std::abs(plane.normal().dot(params.axis)) > max_sin_axis) plane = hypothesis;
  return detail::facing_origin(plane);
}

/// Drops the samples of up to `count` level planes (see Params::remove_level_planes).
void remove_level_planes(Samples& s, int count, const detail::VerticalPlaneRansacParams& vertical,
                         const Thresholds& thresholds, std::mt19937_64& rng) {
  constexpr double kLevelCos = 0.866;        // within 30 deg of horizontal
  constexpr double kMinShare = 0.1;          // of the samples left
  detail::VerticalPlaneRansacParams level = vertical;
  level.max_sin_axis = 1.0;
  level.min_cos_axis = kLevelCos;
  for (int k = 0; k < count && s.points.size() >= 3; ++k) {
    const detail::VerticalPlaneRansacResult found = detail::find_vertical_plane(s.points, level, rng);
    if (!found.found || static_cast<double>(found.consensus) < kMinShare * static_cast<double>(s.points.size()))
      return;
    Samples rest;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      if (std::abs(found.plane.signedDistance(s.points[i])) <= thresholds.inliers(s.points[i])) continue;
      rest.points.push_back(s.points[i]);
      rest.tolerance.push_back(s.tolerance[i]);
    }
    s.points.swap(rest.points);
    s.tolerance.swap(rest.tolerance);
  }
}

/// One extracted plane: its patch and, when board-sized, its refit and inliers.
struct Extraction {
  PlaneCandidate candidate;
  detail::Patch patch;
  Plane patch_plane;  // the plane the patch was found on (its grid's), before the refit
};

void refit(Extraction& e, const std::vector<Eigen::Vector3d>& points, const std::vector<std::size_t>& finite,
           const detail::PlaneGrid& grid, const std::vector<std::size_t>& patch_consensus,
           const PlaneSegmenter::Params& params) {
  // Least-squares refit on the full-cloud consensus, then again on everything
  // within delta_inliers (a thin consensus slice of a noisy stereo cloud leans
  // towards the hypothesis it was cut with).
  PlaneCandidate& c = e.candidate;
  const Thresholds t(params);
  const auto in_patch = [&](std::size_t i) { return detail::in_patch(grid, e.patch, points[i]); };
  std::vector<std::size_t> near;  // patch points within a generous slab: the passes choose among them
  for (std::size_t i : finite)
    if (std::abs(c.plane.signedDistance(points[i])) <= 2.0 * t.inliers(points[i]) && in_patch(i))
      near.push_back(i);
  Plane plane = detail::facing_origin(detail::fit_plane(points, patch_consensus));
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::size_t> wide;
    for (std::size_t i : near)
      if (std::abs(plane.signedDistance(points[i])) <= t.inliers(points[i])) wide.push_back(i);
    if (wide.size() < 3) break;
    plane = detail::facing_origin(detail::fit_plane(points, wide));
  }
  double sum_sq = 0.0;
  for (std::size_t i : patch_consensus) sum_sq += std::pow(plane.signedDistance(points[i]), 2);
  c.plane = plane;
  c.rms = std::sqrt(sum_sq / static_cast<double>(patch_consensus.size()));
  for (std::size_t i : near)  // in index order, as `finite`
    if (std::abs(plane.signedDistance(points[i])) <= t.inliers(points[i])) c.inliers.push_back(i);
}

Extraction measure(const Plane& plane, const std::vector<Eigen::Vector3d>& points,
                   const std::vector<std::size_t>& finite, const Samples& samples,
                   const Target& target, const PlaneSegmenter::Params& params) {
  Extraction e;
  PlaneCandidate& c = e.candidate;
  c.plane = plane;
  const Thresholds t(params);
  std::vector<Eigen::Vector3d> on_plane;
  for (std::size_t i = 0; i < samples.points.size(); ++i)
    if (std::abs(plane.signedDistance(samples.points[i])) <= samples.tolerance[i]) on_plane.push_back(samples.points[i]);
  e.patch_plane = plane;
  const detail::PlaneGrid grid(plane, params.axis, params.patch_gap_horizontal, params.patch_gap_vertical);
  // The window allows the board's size plus tolerance, horizontally long.
  const double tol = 1.0 + params.size_tolerance;
  const Eigen::Vector2d window(tol * std::max(target.board_width, target.board_height),
                               tol * std::min(target.board_width, target.board_height));
  e.patch = detail::largest_patch(grid, on_plane, window, kWindowShare);
  c.extent_long = e.patch.extent_long;
  c.extent_short = e.patch.extent_short;

  // One pass over the full cloud: support, the consensus inside the patch, and
  // the coplanar points around it. Patch membership of each point is looked up
  // once: a dense stereo cloud makes that the segmenter's hot spot.
  IsolationCounter around(e.patch.box, params.isolation_band);
  std::vector<std::size_t> patch_consensus;
  for (std::size_t i : finite) {
    if (std::abs(plane.signedDistance(points[i])) > t.consensus(points[i])) continue;
    ++c.support;
    const Eigen::Vector2d uv = grid.to_plane(points[i]);
    around.add(uv);
    if (detail::in_patch(grid, e.patch, uv)) patch_consensus.push_back(i);
  }
  c.patch_points = patch_consensus.size();
  if (c.support < params.min_support) {
    c.reason = "support " + std::to_string(c.support) + " below min_support";
    return e;
  }
  c.reason = board_mismatch(e.patch, c.patch_points, target, params);
  if (params.keep_oversized && c.reason.rfind(kLargerThanTheBoard, 0) == 0) {
    c.oversized = true;
    c.isolation = around.isolation();
    refit(e, points, finite, grid, patch_consensus, params);
    return e;
  }
  if (!c.reason.empty()) return e;
  c.isolation = around.isolation();
  c.prior = board_prior(c, target, params.size_tolerance);
  c.plausible = true;
  refit(e, points, finite, grid, patch_consensus, params);
  return e;
}

/// Orders the plausible candidates by prior and names the top one the result's plane.
void rank(PlaneSegmenter::Result& result) {
  for (std::size_t i = 0; i < result.candidates.size(); ++i)
    if (result.candidates[i].plausible) result.ranking.push_back(static_cast<int>(i));
  std::stable_sort(result.ranking.begin(), result.ranking.end(), [&](int a, int b) {
    return result.candidates[a].prior > result.candidates[b].prior;
  });
  // Last resorts, in extraction order (most support first).
  for (std::size_t i = 0; i < result.candidates.size(); ++i)
    if (result.candidates[i].oversized) result.ranking.push_back(static_cast<int>(i));
  if (!result.ranking.empty()) {
    const PlaneCandidate& best = result.candidates[result.ranking.front()];
    result.found = true;
    result.plane = best.plane;
    result.inliers = best.inliers;
    result.rms = best.rms;
    return;
  }
  std::ostringstream reason;
  reason << "no board-sized plane among " << result.candidates.size() << " candidate(s)";
  for (std::size_t i = 0; i < result.candidates.size(); ++i)
    reason << (i ? "; " : ": ") << "#" << i << " " << result.candidates[i].reason;
  result.reason = reason.str();
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
  if (remove_level_planes < 0 || remove_level_planes > 4) throw ParamError("remove_level_planes", "must be 0..4");
  if (!(size_tolerance >= 0.0 && size_tolerance < 1.0)) throw ParamError("size_tolerance", "must be in [0, 1)");
  if (!(min_height_fraction >= 0.0 && min_height_fraction <= 1.0))
    throw ParamError("min_height_fraction", "must be in [0, 1]");
  if (!(min_length_fraction >= 0.0 && min_length_fraction <= 1.0))
    throw ParamError("min_length_fraction", "must be in [0, 1]");
  positive(isolation_band, "isolation_band");
  if (!(depth_noise >= 0.0) || !std::isfinite(depth_noise)) throw ParamError("depth_noise", "must be >= 0 (1/m)");
}

PlaneSegmenter::Params PlaneSegmenter::Params::lidar() { return Params{}; }

PlaneSegmenter::Params PlaneSegmenter::Params::stereo() {
  Params params;
  params.inlier_threshold = 0.10;
  params.axis = -Eigen::Vector3d::UnitY();  // optical frame: y points down
  params.patch_gap_horizontal = 0.1;        // dense cloud: holes need not be bridged by one ring
  params.patch_gap_vertical = 0.1;
  params.max_candidates = 6;  // each costs a pass over a dense cloud
  params.remove_level_planes = 2;
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
  std::mt19937_64 rng(params_.seed);
  const Thresholds thresholds(params_);
  Samples s = draw_samples(points, params_.max_samples, thresholds, rng);
  if (s.finite.size() < params_.min_support) {
    result.reason = "only " + std::to_string(s.finite.size()) + " finite points";
    return result;
  }
  detail::VerticalPlaneRansacParams ransac;
  ransac.distance_threshold = params_.distance_threshold;
  ransac.max_sin_axis = std::sin(params_.max_angle);
  ransac.axis = params_.axis;
  ransac.max_iterations = params_.max_iterations;
  ransac.sample_radius = params_.sample_radius;
  ransac.tolerance = &s.tolerance;

  remove_level_planes(s, params_.remove_level_planes, ransac, thresholds, rng);
  for (int k = 0; k < params_.max_candidates && s.points.size() >= 3; ++k) {
    const detail::VerticalPlaneRansacResult found = detail::find_vertical_plane(s.points, ransac, rng);
    if (!found.found) break;
    const Plane plane = refit_hypothesis(found.plane, s, params_, ransac.max_sin_axis);
    Extraction e = measure(plane, points, s.finite, s, target, params_);
    const bool too_small = e.candidate.support < params_.min_support;
    result.candidates.push_back(std::move(e.candidate));
    if (too_small) break;  // candidates come in decreasing support: none left can be the board
    // Drop this patch (thick surfaces too: inlier_threshold) and look again,
    // on the plane and grid the patch was found with: the refit tilts a wide
    // plane enough that its patch cells no longer line up with the samples
    // (a wall split by the board in front of it was found again and again,
    // until the candidates ran out before the board).
    const Plane& cut = e.patch_plane;
    const detail::PlaneGrid grid(cut, params_.axis, params_.patch_gap_horizontal, params_.patch_gap_vertical);
    Samples rest;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const Eigen::Vector3d& p = s.points[i];
      if (std::abs(cut.signedDistance(p)) <= thresholds.inliers(p) && detail::in_patch(grid, e.patch, p)) continue;
      rest.points.push_back(p);
      rest.tolerance.push_back(s.tolerance[i]);
    }
    if (rest.points.size() == s.points.size()) break;
    s.points.swap(rest.points);
    s.tolerance.swap(rest.tolerance);
  }
  rank(result);
  return result;
}

}  // namespace l2s
