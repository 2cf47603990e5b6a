// A planted example for scripts/check_guarded_assertions.py (never compiled):
// each test below checks nothing when nothing is found, and the check must
// name all three. The last test asserts its outcome first and must pass.

TEST(Planted, ChecksOnlyInsideIfFound) {
  const auto result = detect();
  if (result.found) {
    EXPECT_LT(result.error, 0.01);
  }
}

TEST(Planted, SkipsTheRestOfTheLoopWhenNotFound) {
  for (int seed : {1, 2, 3}) {
    const auto result = detect(seed);
    if (!result.found) continue;
    EXPECT_LT(result.error, 0.01) << seed;
  }
}

TEST(Planted, ReturnsEarlyWithoutAResult) {
  const auto result = detect();
  if (!result.success) return;
  EXPECT_EQ(result.count, 4);
}

TEST(Planted, AssertsTheOutcomeFirst) {
  const auto result = detect();
  ASSERT_TRUE(result.found) << result.reason;
  if (result.found) EXPECT_LT(result.error, 0.01);
}
