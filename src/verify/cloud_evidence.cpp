#include "verify/cloud_evidence.hpp"

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

}  // namespace

BoardEvidence cloud_evidence(const std::vector<Eigen::Vector3d>& points, const Plane& plane,
                             const Eigen::Isometry3d& T_sensor_board, const Target& target,
                             const BoardVerifier::Params& verifier, const CloudEvidenceParams& params) {
  BoardEvidence evidence;
  const Eigen::Isometry3d T_board_sensor = T_sensor_board.inverse();
  const std::array<Eigen::Vector2d, 4> holes = target.hole_centers();
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
    const int region = region_of((T_board_sensor * (t * ray)).head<2>(), holes, target, verifier);
    if (region < 0) continue;
    if (region < 4)
      ++(on ? evidence.hole_blocked : evidence.hole_open)[region];
    else
      ++(on ? evidence.outline_blocked : evidence.outline_open);
  }
  return evidence;
}

}  // namespace l2s::detail
