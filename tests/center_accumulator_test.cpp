#include <l2s/center_accumulator.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace l2s {
namespace {

HoleCenters truth() {
  return {Eigen::Vector3d(-0.25, -0.2, 3.0), Eigen::Vector3d(0.25, -0.2, 3.0),
          Eigen::Vector3d(-0.25, 0.2, 3.0), Eigen::Vector3d(0.25, 0.2, 3.0)};
}

HoleCenters noisy(std::mt19937& rng, double sigma) {
  std::normal_distribution<double> noise(0.0, sigma);
  HoleCenters c = truth();
  for (auto& p : c) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  return c;
}

TEST(CenterAccumulator, RecoversCentresDespiteOutlierFrames) {
  for (const auto estimator : {CenterAccumulator::Estimator::Mean, CenterAccumulator::Estimator::GeometricMedian}) {
    CenterAccumulator::Params params;
    params.estimator = estimator;
    CenterAccumulator accumulator(params);
    std::mt19937 rng(11);
    for (int frame = 0; frame < 20; ++frame) accumulator.add(noisy(rng, 0.003));
    // Three wrong frames: a swapped labelling, a far-off centre, a NaN.
    HoleCenters swapped = truth();
    std::swap(swapped[0], swapped[1]);
    accumulator.add(swapped);
    HoleCenters far = noisy(rng, 0.003);
    far[3] += Eigen::Vector3d(0.15, 0.0, 0.0);
    accumulator.add(far);
    HoleCenters with_nan = noisy(rng, 0.003);
    with_nan[2].setConstant(std::numeric_limits<double>::quiet_NaN());
    accumulator.add(with_nan);

    const CenterAccumulator::Result result = accumulator.estimate();
    ASSERT_TRUE(result.found) << result.reason;
    EXPECT_EQ(result.frames, 23);
    // Which frames the estimate left out: the swapped one and the far one
    // (its three other centres are in, one is not); the NaN is no centre.
    std::vector<bool> clustered(23, true);
    clustered[20] = clustered[21] = false;
    EXPECT_EQ(result.clustered, clustered);
    for (int h = 0; h < 4; ++h) {
      EXPECT_LT((result.centers[h] - truth()[h]).norm(), 0.003) << "hole " << h;
      EXPECT_GE(result.counts[h], 20);
      EXPECT_LE(result.counts[h], 22);
      EXPECT_GT(result.spread[h], 0.001);
      EXPECT_LT(result.spread[h], 0.01);
    }
  }
}

TEST(CenterAccumulator, OutlierOutsideToleranceDoesNotMoveCentroid) {
  CenterAccumulator::Params params;
  params.estimator = CenterAccumulator::Estimator::Mean;
  CenterAccumulator accumulator(params);
  for (int frame = 0; frame < 10; ++frame) accumulator.add(truth());
  const HoleCenters before = accumulator.estimate().centers;
  HoleCenters wrong = truth();
  for (auto& p : wrong) p.z() += 0.05;
  accumulator.add(wrong);
  const CenterAccumulator::Result after = accumulator.estimate();
  ASSERT_TRUE(after.found) << after.reason;
  for (int h = 0; h < 4; ++h) EXPECT_LT((after.centers[h] - before[h]).norm(), 1e-12);
}

TEST(CenterAccumulator, ExplainsWhichHoleFailed) {
  CenterAccumulator accumulator;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> scatter(-0.5, 0.5);
  for (int frame = 0; frame < 20; ++frame) {
    HoleCenters c = truth();
    if (frame >= 3) c[0] += Eigen::Vector3d(scatter(rng), scatter(rng), scatter(rng));  // TL wanders
    accumulator.add(c);
  }
  const CenterAccumulator::Result result = accumulator.estimate();
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("hole TL: largest cluster has"), std::string::npos) << result.reason;
  EXPECT_NE(result.reason.find("of 20 centres"), std::string::npos) << result.reason;
  EXPECT_EQ(result.reason.find("hole TR"), std::string::npos) << result.reason;
}

TEST(CenterAccumulator, ResetForgetsFramesAndEmptyFails) {
  CenterAccumulator accumulator;
  EXPECT_FALSE(accumulator.estimate().found);
  accumulator.add(truth());
  EXPECT_TRUE(accumulator.estimate().found);
  accumulator.reset();
  EXPECT_EQ(accumulator.frames(), 0);
  const CenterAccumulator::Result result = accumulator.estimate();
  EXPECT_FALSE(result.found);
  EXPECT_FALSE(result.reason.empty());
}

// A sensor rolled near 90 deg labels by an "up" that flips between frames:
// each frame's labels are turned to agree with the majority's.
TEST(CenterAccumulator, AlignsLabelsTurnedBetweenFrames) {
  const auto turns = quarter_turns();
  ASSERT_EQ(turns.size(), 4u);
  const HolePermutation half = turns[2].permutation;
  ASSERT_EQ(turns[2].degrees, 180);
  std::mt19937 rng(3);
  CenterAccumulator accumulator;
  // The first frame is an outlier (1 m off): the reference must not be it.
  HoleCenters first = noisy(rng, 0.002);
  for (auto& p : first) p.x() += 1.0;
  accumulator.add(first);
  for (int frame = 0; frame < 12; ++frame) {
    const HoleCenters c = noisy(rng, 0.002);
    accumulator.add(frame % 3 == 1 ? relabel(c, half) : c);
  }
  const CenterAccumulator::Result result = accumulator.estimate();
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.relabelled_frames, 4);
  for (int h = 0; h < 4; ++h) EXPECT_LT((result.centers[h] - truth()[h]).norm(), 0.003) << "hole " << h;

  CenterAccumulator::Params paper;
  paper.align_labels = false;
  CenterAccumulator unaligned(paper);
  for (int frame = 0; frame < 12; ++frame) {
    const HoleCenters c = noisy(rng, 0.002);
    unaligned.add(frame % 2 ? relabel(c, half) : c);
  }
  EXPECT_EQ(unaligned.estimate().relabelled_frames, 0);
}

// On a square pattern any quarter turn maps the holes onto themselves.
TEST(CenterAccumulator, AlignsQuarterTurnsOfASquarePattern) {
  Target square = Target::paper2017();
  ASSERT_EQ(hole_symmetries(square).size(), 4u);
  ASSERT_EQ(hole_symmetries(Target{}).size(), 2u);
  HoleCenters base;
  for (int h = 0; h < 4; ++h) base[h] = Eigen::Vector3d(square.hole_centers()[h].x(), -square.hole_centers()[h].y(), 3.0);
  CenterAccumulator accumulator;
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0.0, 0.002);
  const auto turns = quarter_turns();
  for (int frame = 0; frame < 16; ++frame) {
    HoleCenters c = base;
    for (auto& p : c) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    accumulator.add(relabel(c, turns[frame % 4].permutation));
  }
  const CenterAccumulator::Result result = accumulator.estimate();
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.relabelled_frames, 12);
  for (int h = 0; h < 4; ++h) EXPECT_LT((result.centers[h] - base[h]).norm(), 0.003) << "hole " << h;
}

TEST(CenterAccumulator, RejectsInvalidParams) {
  CenterAccumulator::Params params;
  params.cluster_tolerance = -1.0;
  try {
    CenterAccumulator{params};
    FAIL() << "expected ParamError";
  } catch (const ParamError& error) {
    EXPECT_EQ(error.field(), "cluster_tolerance");
  }
}

}  // namespace
}  // namespace l2s
