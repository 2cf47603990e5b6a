// The hypothesise-then-verify loop shared by the branches: which planes it
// tries, in which order, and when it stops.
#include "verify/hypothesis_search.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace l2s::detail {
namespace {

/// Board-sized candidates with the given priors, ranked most board-like first.
PlaneSegmenter::Result planes_with_priors(const std::vector<double>& priors) {
  PlaneSegmenter::Result planes;
  for (std::size_t i = 0; i < priors.size(); ++i) {
    PlaneCandidate candidate;
    candidate.plane = Plane(Eigen::Vector3d(0.0, 0.0, -1.0), 3.0);
    candidate.plausible = true;
    candidate.prior = priors[i];
    planes.candidates.push_back(candidate);
    planes.ranking.push_back(static_cast<int>(i));
  }
  planes.found = true;
  return planes;
}

/// Evidence that verifies, scoring by how many holes were seen through.
BoardEvidence evidence_with_open_holes(int open_holes) {
  BoardEvidence e;
  for (int h = 0; h < open_holes; ++h) e.hole_open[h] = 20;
  e.fit_rms = 0.002;
  e.rim_support = 0.9;
  e.rim_background = 0.05;
  return e;
}

struct Tried {
  std::vector<int> candidates;
};

/// Every candidate shows four holes; the board (candidate 0) scores lower
/// than the pieces of wall after it, as a board whose holes show nothing
/// measurable does.
std::optional<int> run(const PlaneSegmenter::Result& planes, const BoardVerifier::Params& params, Tried& tried) {
  std::vector<BoardHypothesis> log;
  return search_hypotheses<int>(planes, BoardVerifier(params), log, [&](BoardHypothesis& h) -> std::optional<int> {
    tried.candidates.push_back(h.candidate);
    h.evidence = evidence_with_open_holes(h.candidate == 0 ? 1 : 3);
    return h.candidate;
  });
}

TEST(HypothesisSearch, PlanesFarLessBoardLikeThanAVerifiedOneAreNotTried) {
  // Priors as on the paper's setting 2: the board 0.96, strips of the wall
  // behind it 0.16, 0.15 and 0.05. Each strip cost a region's matching and a
  // failed hole search (~100 ms) before.
  const auto planes = planes_with_priors({0.96, 0.16, 0.15, 0.05});
  Tried tried;
  const auto chosen = run(planes, BoardVerifier::Params{}, tried);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, 0);
  EXPECT_EQ(tried.candidates, std::vector<int>{0});
}

TEST(HypothesisSearch, ComparablyBoardLikePlanesStillChallengeAVerifiedOne) {
  const auto planes = planes_with_priors({0.9, 0.6, 0.2});
  Tried tried;
  const auto chosen = run(planes, BoardVerifier::Params{}, tried);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, 1) << "the higher-scoring challenger wins";
  EXPECT_EQ(tried.candidates, (std::vector<int>{0, 1}));
}

TEST(HypothesisSearch, ChallengerPriorZeroTriesEveryPlane) {
  const auto planes = planes_with_priors({0.96, 0.16, 0.15, 0.05});
  BoardVerifier::Params params;
  params.challenger_prior = 0.0;
  Tried tried;
  run(planes, params, tried);
  EXPECT_EQ(tried.candidates, (std::vector<int>{0, 1, 2, 3}));
}

TEST(HypothesisSearch, NothingVerifiedTriesUpToTheLimit) {
  const auto planes = planes_with_priors({0.9, 0.2, 0.1, 0.05, 0.01});
  std::vector<BoardHypothesis> log;
  int calls = 0;
  const auto chosen = search_hypotheses<int>(planes, BoardVerifier(), log, [&](BoardHypothesis& h) -> std::optional<int> {
    ++calls;
    h.stage = "circles";
    h.reason = "no hole pattern";
    return std::nullopt;
  });
  EXPECT_FALSE(chosen.has_value());
  EXPECT_EQ(calls, BoardVerifier::Params{}.max_hypotheses);
}

}  // namespace
}  // namespace l2s::detail
