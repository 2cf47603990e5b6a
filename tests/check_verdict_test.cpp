// The verdict rules on measurements made up for the purpose (the scoring
// that makes them is tested on simulated scenes elsewhere).
#include <l2s/calibration_check.hpp>

#include "check/verdict.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace l2s
