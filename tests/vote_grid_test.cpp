// The vote accumulator of the circle and hole-pattern Hough transforms
// (circles/vote_grid.hpp): its strongest peaks, and that asking for the few
// strongest gives exactly the head of the whole ranking (the pattern search
// asks for three per angle and skips most cells once it holds three).

#include "circles/vote_grid.hpp"

#include <gtest/gtest.h>

#include <random>

namespace l2s::detail {
namespace {

/// `votes` votes over a 1 x 0.6 m box in 1 cm cells. With `on_cells`, each
/// falls on a cell centre with a whole weight: many maxima are then equal,
/// and their order (scan order) must survive the shortcut too.
VoteGrid scattered_votes(std::uint64_t seed, int votes, bool on_cells) {
  constexpr double kCell = 0.01, kMargin = 0.05;
  VoteGrid grid(Eigen::AlignedBox2d(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.6)), kMargin, kCell);
  const Eigen::Vector2d origin = Eigen::Vector2d::Constant(-(kMargin + 2.0 * kCell));  // the grid's first corner
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(0.0, 1.0), y(0.0, 0.6);
  std::uniform_int_distribution<int> column(5, 104), row(5, 64), weight(1, 3);
  for (int i = 0; i < votes; ++i) {
    if (on_cells)
      grid.vote(origin + kCell * Eigen::Vector2d(column(rng) + 0.5, row(rng) + 0.5), static_cast<float>(weight(rng)));
    else
      grid.vote(Eigen::Vector2d(x(rng), y(rng)));
  }
  return grid;
}

TEST(VoteGrid, StrongestPeakIsWhereMostVotesFell) {
  VoteGrid grid(Eigen::AlignedBox2d(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 1.0)), 0.1, 0.01);
  for (int i = 0; i < 50; ++i) grid.vote(Eigen::Vector2d(0.3, 0.7));
  for (int i = 0; i < 20; ++i) grid.vote(Eigen::Vector2d(0.8, 0.2));
  grid.smooth();
  const auto peaks = grid.peaks(2);
  ASSERT_EQ(peaks.size(), 2u);
  EXPECT_NEAR(peaks[0].second.x(), 0.3, 0.01);
  EXPECT_NEAR(peaks[0].second.y(), 0.7, 0.01);
  EXPECT_NEAR(peaks[1].second.x(), 0.8, 0.01);
  EXPECT_NEAR(peaks[1].second.y(), 0.2, 0.01);
  EXPECT_GT(peaks[0].first, peaks[1].first);
}

TEST(VoteGrid, FewStrongestPeaksAreTheHeadOfTheWholeRanking) {
  for (const bool ties : {false, true})
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      VoteGrid grid = scattered_votes(seed, 400, ties);
      if (seed % 2 == 0) grid.smooth();
      const auto all = grid.peaks();
      ASSERT_GT(all.size(), 10u);
      for (const std::size_t k : {1u, 3u, 7u}) {
        const auto head = grid.peaks(k);
        ASSERT_EQ(head.size(), k);
        for (std::size_t i = 0; i < k; ++i) {
          EXPECT_EQ(head[i].first, all[i].first) << "seed " << seed << " k " << k << " peak " << i;
          EXPECT_EQ(head[i].second, all[i].second) << "seed " << seed << " k " << k << " peak " << i;
        }
      }
      EXPECT_TRUE(grid.peaks(0).empty());
      EXPECT_EQ(grid.peaks(all.size() + 5).size(), all.size());
    }
}

}  // namespace
}  // namespace l2s::detail
