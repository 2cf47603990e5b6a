// The known hole spacing as a constraint (paper Sec. III-C: "the distance
// between the circle centers in the physical calibration target is also taken
// into account") and the labels TL/TR/BL/BR (Sec. III-D).
//
// Labels come from the board's own geometry, not from azimuths: in the plane
// frame (x right, y = sensor up projected into the plane, z towards the
// sensor) the pattern is fitted by a proper 2D rotation for every assignment
// of candidates to holes, and the assignment whose rotation is nearest to
// upright wins. A rectangle admits 0 and 180 degrees (up decides); a square
// admits four rotations (up alone decides). A board seen from behind or beside
// the sensor is labelled as the sensor sees it.
#include "circles/hole_pattern.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace l2s::detail {
namespace {

struct Fit {
  double angle;
  Eigen::Vector2d offset;
  double max_error;
};

/// Rigid 2D fit of holes[h] -> points[h] (Procrustes, rotation only).
Fit rigid_fit(const std::array<Eigen::Vector2d, 4>& holes, const std::array<Eigen::Vector2d, 4>& points) {
  Eigen::Vector2d hole_mean = Eigen::Vector2d::Zero(), point_mean = Eigen::Vector2d::Zero();
  for (int h = 0; h < 4; ++h) hole_mean += holes[h] / 4.0, point_mean += points[h] / 4.0;
  double s_cos = 0.0, s_sin = 0.0;
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector2d a = holes[h] - hole_mean, b = points[h] - point_mean;
    s_cos += a.dot(b);
    s_sin += a.x() * b.y() - a.y() * b.x();
  }
  Fit fit{std::atan2(s_sin, s_cos), Eigen::Vector2d::Zero(), 0.0};
  const Eigen::Rotation2Dd R(fit.angle);
  fit.offset = point_mean - R * hole_mean;
  for (int h = 0; h < 4; ++h) fit.max_error = std::max(fit.max_error, (R * holes[h] + fit.offset - points[h]).norm());
  return fit;
}

// A set of four candidates that fits the pattern, with its best labelling.
struct SetFit {
  std::array<int, 4> candidate_of_hole;
  Fit fit;
  std::size_t support;  // edge points on the four circles
};

/// compatible[a][b]: candidates a and b are a known hole distance apart (a
/// side or a diagonal). Pairs that are not prune the search over sets of four.
std::vector<std::vector<bool>> compatible_pairs(const std::vector<Eigen::Vector2d>& centers,
                                                const std::array<Eigen::Vector2d, 4>& holes, double tolerance) {
  const int n = static_cast<int>(centers.size());
  std::vector<double> hole_distances;
  for (int h = 0; h < 4; ++h)
    for (int k = h + 1; k < 4; ++k) hole_distances.push_back((holes[h] - holes[k]).norm());
  std::vector<std::vector<bool>> compatible(n, std::vector<bool>(n, false));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (const double distance : hole_distances)
        if (a != b && std::abs((centers[a] - centers[b]).norm() - distance) <= 2.0 * tolerance)
          compatible[a][b] = true;
  return compatible;
}

/// The labelling of the sorted set {a, b, c, d} whose fit is within
/// tolerance and nearest to upright, if any; best_miss keeps the smallest
/// fit error seen.
std::optional<SetFit> best_labelling(const std::array<int, 4>& set, const std::vector<Eigen::Vector2d>& centers,
                                     const std::vector<std::size_t>& support,
                                     const std::array<Eigen::Vector2d, 4>& holes, double tolerance,
                                     double& best_miss) {
  std::array<int, 4> perm = set;  // sorted: next_permutation visits all 24
  std::optional<SetFit> set_fit;
  do {
    const std::array<Eigen::Vector2d, 4> points{
        {centers[perm[0]], centers[perm[1]], centers[perm[2]], centers[perm[3]]}};
    const Fit fit = rigid_fit(holes, points);
    best_miss = std::min(best_miss, fit.max_error);
    if (fit.max_error > tolerance) continue;
    if (!set_fit || std::abs(fit.angle) < std::abs(set_fit->fit.angle))
      set_fit = SetFit{perm, fit, support[set[0]] + support[set[1]] + support[set[2]] + support[set[3]]};
  } while (std::next_permutation(perm.begin(), perm.end()));
  return set_fit;
}

struct SetSearch {
  std::vector<SetFit> fits;
  double best_miss = std::numeric_limits<double>::infinity();  // [m] smallest fit error of any labelling
};

/// Every set of four pairwise compatible candidates that fits, with its best labelling.
SetSearch fitting_sets(const std::vector<Eigen::Vector2d>& centers, const std::vector<std::size_t>& support,
                       const std::array<Eigen::Vector2d, 4>& holes, double tolerance) {
  const int n = static_cast<int>(centers.size());
  const std::vector<std::vector<bool>> compatible = compatible_pairs(centers, holes, tolerance);
  SetSearch search;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = c + 1; d < n; ++d) {
          if (!(compatible[a][b] && compatible[a][c] && compatible[a][d] && compatible[b][c] &&
                compatible[b][d] && compatible[c][d]))
            continue;
          if (const auto set_fit =
                  best_labelling({{a, b, c, d}}, centers, support, holes, tolerance, search.best_miss))
            search.fits.push_back(*set_fit);
        }
  return search;
}

}  // namespace

PatternMatch match_hole_pattern(const std::vector<Eigen::Vector2d>& centers,
                                const std::vector<std::size_t>& support,
                                const std::array<Eigen::Vector2d, 4>& holes, double tolerance,
                                double same_board_distance) {
  PatternMatch match;
  const int n = static_cast<int>(centers.size());
  if (n < 4) {
    match.reason = "only " + std::to_string(n) + " circle candidate(s), 4 holes needed";
    return match;
  }
  const SetSearch search = fitting_sets(centers, support, holes, tolerance);
  const std::vector<SetFit>& fits = search.fits;
  if (fits.empty()) {
    std::ostringstream reason;
    reason << "no four of the " << n << " circle candidates form the hole pattern (closest set misses by "
           << search.best_miss << " m, tolerance " << tolerance << " m)";
    match.reason = reason.str();
    return match;
  }
  // The best-supported set is the board. Sets that put the pattern at (nearly)
  // the same place are that board with a spurious extra candidate near a hole.
  // A set elsewhere with comparable support is a second pattern, and the frame
  // cannot be trusted; one made of weak candidates (texture, clutter) is not.
  const auto best = std::min_element(fits.begin(), fits.end(), [](const SetFit& x, const SetFit& y) {
    if (x.support != y.support) return x.support > y.support;
    return x.fit.max_error < y.fit.max_error;
  });
  for (const SetFit& other : fits)
    if ((other.fit.offset - best->fit.offset).norm() > same_board_distance &&
        2 * other.support >= best->support) {
      std::ostringstream reason;
      reason << "more than one set of four circle candidates fits the hole pattern (ambiguous: pattern "
             << "centres (" << best->fit.offset.x() << ", " << best->fit.offset.y() << ") and ("
             << other.fit.offset.x() << ", " << other.fit.offset.y() << ") m in the board plane)";
      match.reason = reason.str();
      return match;
    }
  match.found = true;
  match.candidate_of_hole = best->candidate_of_hole;
  match.angle = best->fit.angle;
  match.offset = best->fit.offset;
  return match;
}

}  // namespace l2s::detail
