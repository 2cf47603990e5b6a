// The frames the Calibrator keeps for its check (calibrator/check_keeper.hpp):
// evenly spread and bounded; while frames with the board on both sides are
// fewer than the target, frames without it fill in (a ring-free lidar finds
// the board once per accumulated window, and one frame's evidence is thin).

#include <l2s/scene_observer.hpp>

#include "calibrator/check_keeper.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace l2s::detail {
namespace {

using Kind = CheckFrameKeeper::Kind;

/// Offers `kinds` in order (frame i named "b<i>" or "s<i>"); returns the kept names.
std::vector<std::string> offer(CheckFrameKeeper& keeper, const std::string& kinds) {
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const Kind kind = kinds[i] == 'b' ? Kind::Board : Kind::Scene;
    if (keeper.wants_next(kind))
      keeper.keep(kind, CheckFrame{kinds.substr(i, 1) + std::to_string(i), {}, {}});
    else
      keeper.skip(kind);
  }
  std::vector<std::string> names;
  for (const CheckFrame& frame : keeper.frames()) names.push_back(frame.id);
  return names;
}

TEST(CheckFrameKeeper, ManyBoardFramesAreThinnedEvenlyAndSceneFramesStayOut) {
  CheckFrameKeeper keeper(2);
  // 12 board frames: the stride doubles when a fifth is held, and again
  // later; the scene frame held before the second board frame goes with it.
  const auto names = offer(keeper, "bsbbsbbbbbbbbb");
  EXPECT_EQ(names, (std::vector<std::string>{"b0", "b6", "b10"}));
  EXPECT_EQ(keeper.board_frames(), 3);
}

TEST(CheckFrameKeeper, FewBoardFramesAreFilledUpWithSceneFrames) {
  CheckFrameKeeper keeper(4);
  // One board frame in 12: every scene frame is offered until 8 are held,
  // then every second of them stays.
  const auto names = offer(keeper, "sssssbssssss");
  EXPECT_EQ(keeper.board_frames(), 1);
  EXPECT_EQ(names, (std::vector<std::string>{"s0", "s2", "s4", "b5", "s7", "s9", "s11"}));
}

TEST(CheckFrameKeeper, SceneFramesGoOnceTheBoardFramesReachTheTarget) {
  CheckFrameKeeper keeper(2);
  const auto names = offer(keeper, "ssbsbss");
  EXPECT_EQ(names, (std::vector<std::string>{"b2", "b4"}));
  keeper.reset();
  EXPECT_TRUE(keeper.frames().empty());
  EXPECT_EQ(offer(keeper, "s"), (std::vector<std::string>{"s0"}));
}

}  // namespace
}  // namespace l2s::detail
