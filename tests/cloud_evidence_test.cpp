// A board's evidence from a cloud seen from its origin (verify/cloud_evidence):
// returns on the plane inside a hole block it, returns behind see through
// it; a cloud that covers the board all over (a ring-free window) also shows
// a hole by the returns it lacks against the face around it.

#include "verify/cloud_evidence.hpp"

#include <l2s/board_verifier.hpp>

#include <gtest/gtest.h>

#include <random>

namespace l2s::detail {
namespace {

/// The board 3 m ahead of a lidar (x forward, z up), facing it.
Eigen::Isometry3d board_ahead() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = -Eigen::Vector3d::UnitY();  // board right
  T.linear().col(1) = Eigen::Vector3d::UnitZ();   // board up
  T.linear().col(2) = -Eigen::Vector3d::UnitX();  // towards the lidar
  T.translation() = Eigen::Vector3d(3.0, 0.0, 0.0);
  return T;
}

/// `count` returns spread over the board's face (and its holes unless
/// `solid`), `strays` more on the plane inside each hole (mixed returns),
/// none behind: open space. Holes left of `view_edge` [m, board x] are out of
/// view with the face around them.
std::vector<Eigen::Vector3d> face_returns(const Target& target, bool solid, int count, int strays,
                                          double view_edge = -1e9) {
  const Eigen::Isometry3d T = board_ahead();
  const auto holes = target.hole_centers();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(-0.5 * target.board_width, 0.5 * target.board_width);
  std::uniform_real_distribution<double> y(-0.5 * target.board_height, 0.5 * target.board_height);
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < count) {
    const Eigen::Vector2d q(x(rng), y(rng));
    if (q.x() < view_edge) continue;
    bool in_hole = false;
    for (const Eigen::Vector2d& h : holes) in_hole = in_hole || (q - h).norm() < target.hole_radius;
    if (in_hole && !solid) continue;
    points.push_back(T * Eigen::Vector3d(q.x(), q.y(), 0.0));
  }
  for (const Eigen::Vector2d& h : holes)
    for (int k = 0; k < strays && h.x() >= view_edge; ++k)
      points.push_back(T * Eigen::Vector3d(h.x() + 0.01 * k, h.y(), 0.0));
  return points;
}

BoardEvidence evidence_of(const std::vector<Eigen::Vector3d>& points, const Target& target, bool count_missing) {
  const Plane plane(Eigen::Vector3d::UnitX(), -3.0);
  CloudEvidenceParams params;
  params.count_missing_returns = count_missing;
  return cloud_evidence(points, plane, board_ahead(), target, BoardVerifier::Params{}, params);
}

TEST(CloudEvidence, HolesWithNothingBehindShowByTheReturnsTheyLack) {
  const Target target;
  const auto points = face_returns(target, false, 20000, 8);
  const BoardEvidence plain = evidence_of(points, target, false);
  EXPECT_EQ(plain.hole_open[0], 0);
  EXPECT_EQ(plain.hole_blocked[0], 8);
  EXPECT_FALSE(BoardVerifier().judge(plain).verified) << "eight strays and no return behind: covered";
  const BoardEvidence dense = evidence_of(points, target, true);
  // 20000 returns over the board's 1.4 m^2 less its holes: ~400 in a hole's open disc.
  for (int h = 0; h < 4; ++h) {
    EXPECT_GT(dense.hole_open[h], 250) << "hole " << h;
    EXPECT_EQ(dense.hole_blocked[h], 8) << "hole " << h;
  }
  EXPECT_TRUE(BoardVerifier().judge(dense).verified) << BoardVerifier().judge(dense).reason;
}

TEST(CloudEvidence, ASurfaceWithoutHolesStaysCovered) {
  const Target target;
  const BoardEvidence e = evidence_of(face_returns(target, true, 20000, 0), target, true);
  for (int h = 0; h < 4; ++h) EXPECT_LT(e.hole_open[h], 0.2 * e.hole_blocked[h]) << "hole " << h;
  EXPECT_FALSE(BoardVerifier().judge(e).verified);
}

TEST(CloudEvidence, AHoleOutOfViewLacksNothing) {
  const Target target;
  // The left half of the board out of the field of view: its two holes give no evidence either way.
  const BoardEvidence e = evidence_of(face_returns(target, false, 10000, 0, 0.0), target, true);
  const auto holes = target.hole_centers();
  for (int h = 0; h < 4; ++h) {
    if (holes[h].x() < 0.0) {
      EXPECT_EQ(e.hole_open[h] + e.hole_blocked[h], 0) << "hole " << h;
    } else {
      EXPECT_GT(e.hole_open[h], 150) << "hole " << h;
    }
  }
}

}  // namespace
}  // namespace l2s::detail
