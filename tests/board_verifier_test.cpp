// The verdict on one board hypothesis from its evidence.
#include <l2s/board_verifier.hpp>
#include <l2s/error.hpp>

#include <gtest/gtest.h>

namespace l2s {
namespace {

/// Evidence of a board that passes: open holes, clear outline, tight and
/// confirmed rims.
BoardEvidence a_good_board() {
  BoardEvidence e;
  for (int h = 0; h < 4; ++h) e.hole_open[h] = 20;
  e.outline_open = 30;
  e.fit_rms = 0.002;
  e.rim_support = 0.8;
  e.rim_background = 0.1;
  return e;
}

TEST(BoardVerifier, AGoodBoardIsVerified) {
  const auto verdict = BoardVerifier().judge(a_good_board());
  EXPECT_TRUE(verdict.verified) << verdict.reason;
  EXPECT_GT(verdict.score, 0.5);
}

TEST(BoardVerifier, AHoleThatLooksLikeTheFaceAroundItAndMatchesOnThePlaneIsCovered) {
  BoardEvidence e = a_good_board();
  e.hole_open[2] = 3;
  e.hole_blocked[2] = 12;
  e.hole_look_difference[2] = 0.5;  // covered wall patches: <= 0.5
  const auto verdict = BoardVerifier().judge(e);
  EXPECT_FALSE(verdict.verified);
  EXPECT_NE(verdict.reason.find("bottom-left hole is covered"), std::string::npos) << verdict.reason;
}

// A brick wall far behind the board, seen through a hole, can match one brick
// period off at exactly the plane's disparity; its inside then looks unlike
// the board's face. Those samples are no evidence, not a cover.
TEST(BoardVerifier, AHoleUnlikeTheFaceAroundItIsNotCoveredWhateverItsSamplesMatched) {
  BoardEvidence e = a_good_board();
  e.hole_open[2] = 3;
  e.hole_blocked[2] = 12;
  e.hole_look_difference[2] = 3.0;
  const auto verdict = BoardVerifier().judge(e);
  EXPECT_TRUE(verdict.verified) << verdict.reason;
  EXPECT_NE(verdict.reason.find("unlike the face"), std::string::npos) << verdict.reason;
  EXPECT_LT(verdict.score, BoardVerifier().judge(a_good_board()).score);  // counted as half open
}

TEST(BoardVerifier, RejectsANonPositiveLookDifference) {
  BoardVerifier::Params params;
  params.min_look_difference = 0.0;
  EXPECT_THROW(BoardVerifier{params}, ParamError);
}

}  // namespace
}  // namespace l2s
