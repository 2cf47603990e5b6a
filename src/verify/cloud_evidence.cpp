#include "verify/cloud_evidence.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

/// Where a board-plane position falls: a hole (0..3), the outline band (4), or nothing (-1).
int region_of(const Eigen::Vector2d& q, const std::array<Eigen::Vector2d, 4>& holes, const Target& target,
              const BoardVerifier::Params& verifier) {
  const double open_radius = target.hole_radius - verifier.hole_margin;
  for (int h = 0; h < 4; ++h)
    if ((q - holes[h]).norm() < open_radius) return h;
  const double inner_x = 0.5 * target.board_width + verifier.outline_gap;
  const double inner_y = 0.5 * target.board_height + verifier.outline_gap;
  const double ax = std::abs(q.x()), ay = std::abs(q.y());
  const bool in_outer = ax <= inner_x + verifier.outline_width && ay <= inner_y + verifier.outline_width;
  const bool in_inner = ax <= inner_x && ay <= inner_y;
  return in_outer && !in_inner ? 4 : -1;
}

constexpr double kAroundWidth = 0.05;  ///< [m] the ring of face around each hole that gives its density

/// The hole whose ring of face (kAroundWidth beyond its rim margin, inside
/// the outline) a board-plane position lies in, or -1.
int face_ring_of(const Eigen::Vector2d& q, const std::array<Eigen::Vector2d, 4>& holes, const Target& target,
                 const BoardVerifier::Params& verifier) {
  if (std::abs(q.x()) > 0.5 * target.board_width || std::abs(q.y()) > 0.5 * target.board_height) return -1;
  const double inner = target.hole_radius + verifier.hole_margin;
  int ring = -1;
  for (int h = 0; h < 4; ++h) {
    const double d = (q - holes[h]).norm();
    if (d < inner) return -1;  // a hole's rim margin or inside: not the face
    if (d < inner + kAroundWidth && ring < 0) ring = h;
  }
  return ring;
}

/// Adds to each hole's open samples the returns a solid face would have
/// given inside it beyond those that came (on the plane or behind it), at
/// the density of on-plane returns on the face around it. Where the sensor
/// does not look (a field of view's edge across the hole) the face around
/// it has no returns either, and nothing is added. The outline band gets
/// the same at the face's mean density: a cloud cropped to the board, or a
/// board before open sky, has nothing beyond its edges, where a wall that
/// continues the plane gives returns as densely as the face.
void count_missing_returns(const std::array<int, 4>& around, const Target& target,
                           const BoardVerifier::Params& verifier, BoardEvidence& evidence) {
  const double inner = target.hole_radius + verifier.hole_margin;
  const double ring_area = M_PI * ((inner + kAroundWidth) * (inner + kAroundWidth) - inner * inner);
  const double open_radius = std::max(0.0, target.hole_radius - verifier.hole_margin);
  for (int h = 0; h < 4; ++h) {
    const double expected = around[h] / ring_area * M_PI * open_radius * open_radius;
    const double missing = expected - evidence.hole_open[h] - evidence.hole_blocked[h];
    if (missing > 0.0) evidence.hole_open[h] += static_cast<int>(std::floor(missing));
  }
  const double density = (around[0] + around[1] + around[2] + around[3]) / (4.0 * ring_area);
  const double inner_x = 0.5 * target.board_width + verifier.outline_gap;
  const double inner_y = 0.5 * target.board_height + verifier.outline_gap;
  const double band_area = 4.0 * ((inner_x + verifier.outline_width) * (inner_y + verifier.outline_width) -
                                  inner_x * inner_y);
  const double missing = density * band_area - evidence.outline_open - evidence.outline_blocked;
  if (missing > 0.0) evidence.outline_open += static_cast<int>(std::floor(missing));
}

}  // namespace

BoardEvidence cloud_evidence(const std::vector<Eigen::Vector3d>& points, const Plane& plane,
                             const Eigen::Isometry3d& T_sensor_board, const Target& target,
                             const BoardVerifier::Params& verifier, const CloudEvidenceParams& params) {
  BoardEvidence evidence;
  const Eigen::Isometry3d T_board_sensor = T_sensor_board.inverse();
  const std::array<Eigen::Vector2d, 4> holes = target.hole_centers();
  std::array<int, 4> around{};  // on-plane returns on the face around each hole
  for (const Eigen::Vector3d& p : points) {
    const double range = p.norm();
    if (!std::isfinite(range) || range < 1e-9) continue;
    const Eigen::Vector3d ray = p / range;
    const double denom = plane.normal().dot(ray);
    if (std::abs(denom) < 1e-6) continue;
    const double t = -plane.offset() / denom;  // where the ray meets the plane
    if (t <= 0.0) continue;
    const bool on = std::abs(range - t) <= params.on_plane;
    const bool past = range >= t + params.behind;
    if (!on && !past) continue;
    const Eigen::Vector2d q = (T_board_sensor * (t * ray)).head<2>();
    const int region = region_of(q, holes, target, verifier);
    if (region < 0) {
      const bool counted = on && params.count_missing_returns;  // the face's density, only when it is used
      if (const int h = counted ? face_ring_of(q, holes, target, verifier) : -1; h >= 0) ++around[h];
      continue;
    }
    if (region < 4)
      ++(on ? evidence.hole_blocked : evidence.hole_open)[region];
    else
      ++(on ? evidence.outline_blocked : evidence.outline_open);
  }
  if (params.count_missing_returns) count_missing_returns(around, target, verifier, evidence);
  return evidence;
}

}  // namespace l2s::detail
