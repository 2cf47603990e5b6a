#pragma once
// Which four circle candidates are the board's holes, and which is which
// (private to the library).

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace l2s::detail {

struct PatternMatch {
  bool found = false;
  std::string reason;
  std::array<int, 4> candidate_of_hole{{-1, -1, -1, -1}};  // ordered as enum Hole
  double angle = 0.0;                                      // [rad] pattern roll in the plane
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();        // [m] pattern centre in the plane
};

/// Finds the one set of four `centers` (in-plane, x right, y up) that a rigid
/// motion of `holes` (ordered as enum Hole) reaches within `tolerance`, and
/// labels it with the proper rotation nearest to upright. `support[i]` counts
/// the edge points on candidate i; the best-supported fitting set wins, and a
/// fitting set farther than `same_board_distance` from it with at least half
/// its support makes the frame ambiguous.
PatternMatch match_hole_pattern(const std::vector<Eigen::Vector2d>& centers,
                                const std::vector<std::size_t>& support,
                                const std::array<Eigen::Vector2d, 4>& holes, double tolerance,
                                double same_board_distance);

}  // namespace l2s::detail
