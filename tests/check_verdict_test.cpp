// The verdict rules on measurements made up for the purpose (the scoring
// that makes them is tested on simulated scenes elsewhere).
#include <l2s/calibration_check.hpp>

#include "check/verdict.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace l2s {
namespace {

using Verdict = CalibrationCheck::Verdict;

// A report whose every measurement agrees with the transform.
CalibrationCheck::Report agreeing() {
  CalibrationCheck::Report report;
  report.board_frames = 3;
  report.edge_frames = 3;
  auto& s = report.scores;
  s.edge_points = 500;
  s.plane_offset = 0.002;
  s.plane_offset_px = 0.01;
  s.plane_tilt = 0.001;
  s.outline_px = 1.0;
  s.outside_fraction = 0.0;
  s.center_offset = 0.001;
  s.depth_bias = 0.0;
  s.depth_tilt = 0.0;
  for (auto& peak : report.peaks) peak.prominence = 0.8;
  return report;
}

bool names_the_plane_offset(const CalibrationCheck::Report& report) {
  for (const std::string& reason : report.reasons)
    if (reason.find("from the camera's board plane") != std::string::npos) return true;
  return false;
}

// A board 3.9 m away seen with fx B = 91 px m: SGBM's sub-pixel bias of a
// quarter pixel puts the stereo plane 38 mm behind the lidar board (a random
// scene's good calibration was suspect for it). The same offset where it is
// a whole pixel of disparity (a long baseline, or a nearer board) is not bias.
TEST(CheckVerdict, PlaneOffsetCountsOnlyBeyondTheStereoPlanesDisparityBias) {
  const CalibrationCheck::Params params;
  CalibrationCheck::Report report = agreeing();
  detail::judge(report, params, 1000.0);
  EXPECT_EQ(report.verdict, Verdict::Ok);

  report = agreeing();
  report.scores.plane_offset = 0.038;
  report.scores.plane_offset_px = 0.26;
  detail::judge(report, params, 1000.0);
  EXPECT_EQ(report.verdict, Verdict::Ok) << report.reasons.front();

  report = agreeing();
  report.scores.plane_offset = 0.038;
  report.scores.plane_offset_px = 1.2;
  detail::judge(report, params, 1000.0);
  EXPECT_EQ(report.verdict, Verdict::Suspect);
  EXPECT_TRUE(names_the_plane_offset(report));

  report = agreeing();  // no depth scale known: graded in metres alone
  report.scores.plane_offset = 0.038;
  report.scores.plane_offset_px = CalibrationCheck::Scores::kNaN;
  detail::judge(report, params, 1000.0);
  EXPECT_TRUE(names_the_plane_offset(report));
}

// Coarse stereo of a plain or dark wall tilts by 2-6 deg against a right
// transform's lidar depths (randomised scenes), so the tilt alone makes a
// result suspect; only a tilt beyond such noise fails it.
TEST(CheckVerdict, DepthTiltAloneMakesAResultSuspect) {
  const CalibrationCheck::Params params;
  CalibrationCheck::Report report = agreeing();
  report.scores.depth_tilt = 4.6 * M_PI / 180;
  detail::judge(report, params, 1000.0);
  EXPECT_EQ(report.verdict, Verdict::Suspect);

  report = agreeing();
  report.scores.depth_tilt = 12.0 * M_PI / 180;
  detail::judge(report, params, 1000.0);
  EXPECT_EQ(report.verdict, Verdict::Failed);
}

// A wrong transform puts lidar returns on pixels of other surfaces: most of
// them disagree with stereo, however well the board evidence agrees (a
// camera that took a wall patch for the board, or a fit turned about a far
// board). A handful of returns is too little to judge by.
TEST(CheckVerdict, DepthAgreementJudgesWhenThereAreEnoughReturns) {
  const CalibrationCheck::Params params;
  const auto judged = [&](double agreement, int points) {
    CalibrationCheck::Report report = agreeing();
    report.scores.depth_agreement = agreement;
    report.scores.depth_points = points;
    detail::judge(report, params, 1000.0);
    return report.verdict;
  };
  EXPECT_EQ(judged(0.95, 5000), Verdict::Ok);
  EXPECT_EQ(judged(0.45, 5000), Verdict::Suspect);
  EXPECT_EQ(judged(0.20, 5000), Verdict::Failed);
  EXPECT_EQ(judged(0.20, 50), Verdict::Ok);
}

// The edges' best alignment near the transform says how far the overlay is
// off only where it is a real alignment: it must beat the transform's own
// score, and put a good share of the edges on image edges (a weak optimum is
// a shadow or texture that six degrees of freedom found to lean on).
TEST(CheckVerdict, MisalignmentCountsOnlyAtARealOptimum) {
  const CalibrationCheck::Params params;
  const auto judged = [&](double gain, double optimum) {
    CalibrationCheck::Report report = agreeing();
    report.misalignment = 2.0 * M_PI / 180;
    report.misalignment_gain = gain;
    report.optimum_edge_score = optimum;
    detail::judge(report, params, 1000.0);
    return report.verdict;
  };
  EXPECT_EQ(judged(0.3, 0.6), Verdict::Failed);
  EXPECT_EQ(judged(0.05, 0.6), Verdict::Ok);  // a flat score: the optimum is anywhere on its top
  EXPECT_EQ(judged(0.3, 0.2), Verdict::Ok);
}

}  // namespace
}  // namespace l2s
