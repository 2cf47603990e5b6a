// summary.md of `l2s suite`: the statistics per cell, the tables per
// experiment, the scene check's verdicts by true error, the random scenes
// split by what was drawn, and the poses experiment's coverage.

#include <l2s/sim/suite.hpp>
#include <l2s/sim/suite_results.hpp>

#include "support/suite_rows.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace l2s::sim {
namespace {

TEST(SuiteStats, MedianAndInterquartileRangeInterpolateLinearly) {
  EXPECT_DOUBLE_EQ(percentile({3.0, 1.0, 2.0}, 50.0), 2.0);
  EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 50.0), 2.5);
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0, 3.0, 4.0, 5.0}, 25.0), 2.0);
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0, 3.0, 4.0}, 75.0), 3.25);  // numpy: 3.25
  EXPECT_TRUE(std::isnan(percentile({}, 50.0)));

  std::vector<SuiteRow> rows(5, sample_row());
  for (int i = 0; i < 5; ++i) rows[i].e_t = 0.001 * (i + 1);
  rows[4].success = false;  // counted, not in the errors
  std::vector<const SuiteRow*> pointers;
  for (const auto& row : rows) pointers.push_back(&row);
  const SuiteStats stats = suite_stats(pointers);
  EXPECT_EQ(stats.runs, 5);
  EXPECT_EQ(stats.successes, 4);
  EXPECT_DOUBLE_EQ(stats.success_rate(), 0.8);
  EXPECT_NEAR(stats.e_t_median, 0.0025, 1e-15);
  EXPECT_NEAR(stats.e_t_iqr, 0.0015, 1e-15);
}

TEST(SuiteStats, SummaryHasATablePerExperimentAndTheFailures) {
  std::vector<SuiteRow> rows(2, sample_row());
  rows[1].success = false;
  rows[1].reason = "the board was never found in 30 frames";
  const std::string summary = suite_summary_markdown(rows);
  EXPECT_NE(summary.find("## noise"), std::string::npos);
  EXPECT_NE(summary.find("| vlp16 | 2 | paper | 30 | 4 | 2 | 50 % | 1.23 |"), std::string::npos) << summary;
  EXPECT_NE(summary.find("1 x the board was never found in # frames"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("scene check"), std::string::npos) << "no verdicts, no section";
}

TEST(SuiteStats, SummarySortsTheVerdictsByTheTrueError) {
  std::vector<SuiteRow> rows(3, sample_row());
  for (int i = 0; i < 3; ++i) rows[i].setting = i + 1;  // three cells
  rows[0].e_t = 0.001, rows[0].e_r = 0.001, rows[0].verdict = "ok";      // good
  rows[1].e_t = 0.3, rows[1].e_r = 0.001, rows[1].verdict = "failed";    // off
  rows[2].e_t = 0.05, rows[2].e_r = 0.001, rows[2].verdict = "suspect";  // in between
  const std::string summary = suite_summary_markdown(rows);
  EXPECT_NE(summary.find("| within 2 cm and 0.5 deg | 1 | 1 | 0 | 0 |"), std::string::npos) << summary;
  EXPECT_NE(summary.find("| in between | 1 | 0 | 1 | 0 |"), std::string::npos) << summary;
  EXPECT_NE(summary.find("| beyond 10 cm or 2 deg | 1 | 0 | 0 | 1 |"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("were not ok"), std::string::npos) << "no false alarm, no list";
  EXPECT_EQ(summary.find("called ok"), std::string::npos) << "no missed error, no list";
}

// Random scenes split by what was drawn, and the silently wrong results
// listed: ok, off by more than 2 cm or 0.5 deg, and beyond their stated bound.
TEST(SuiteStats, ScenesSummarySplitsByWhatWasDrawnAndListsTheSilentlyWrong) {
  std::vector<SuiteRow> rows(4, sample_row());
  for (int i = 0; i < 4; ++i) {
    rows[i].experiment = "scenes";
    rows[i].setting = i + 1;
    rows[i].e_t = 0.003, rows[i].e_r = 0.001, rows[i].verdict = "ok";
    rows[i].bound_t = 0.04, rows[i].bound_r = 0.01;
    rows[i].face = i < 2 ? "matte" : "speckle";
    rows[i].roll = i == 3 ? M_PI : 0.0;
    rows[i].lens = "rectified";
  }
  rows[1].e_t = 0.03;   // wrong, within its bound: honest
  rows[2].e_t = 0.185;  // wrong, beyond its bound: silently wrong
  rows[2].markers = "DICT_6X6_250";
  rows[3].success = false;
  const std::string summary = suite_summary_markdown(rows);
  EXPECT_NE(summary.find("| matte | 2 | 2 | 16.5 | 0.06 | 1 / 0 / 0 | 0 |"), std::string::npos) << summary;
  EXPECT_NE(summary.find("| speckle | 2 | 1 | 185.0 | 0.06 | 1 / 0 / 0 | 1 |"), std::string::npos) << summary;
  EXPECT_NE(summary.find("| markers | 1 | 1 |"), std::string::npos) << summary;
  EXPECT_NE(summary.find("| > 100 deg | 1 | 0 |"), std::string::npos) << summary;
  EXPECT_NE(summary.find("- paper: 1 of 3 calibrated\n  - scene 3 (seed 123456789; ): 185.0 mm"), std::string::npos)
      << summary;
}

// Stereo beside its left camera alone, scene by scene on marked boards: the
// scenes where one camera did better than two are listed.
TEST(SuiteStats, ScenesSummaryWeighsStereoAgainstItsLeftCameraAlone) {
  std::vector<SuiteRow> rows;
  for (int scene = 1; scene <= 4; ++scene)
    for (const char* preset : {"default", "mono"}) {
      SuiteRow row = sample_row();
      row.experiment = "scenes";
      row.setting = scene;
      row.preset = preset;
      row.markers = scene < 4 ? "DICT_6X6_250" : "";  // scene 4: no markers, not weighed
      row.e_t = 0.003;
      rows.push_back(row);
    }
  rows[2].e_t = 0.0045;     // scene 2: stereo 4.5 mm against mono 3 mm
  rows[4].success = false;  // scene 3: stereo failed, mono calibrated
  const std::string summary = suite_summary_markdown(rows);
  EXPECT_NE(summary.find("on the 3 scenes whose board carries markers: both calibrated 2, the stereo result within "
                         "1 mm of the mono one or nearer the truth in 1 of them; stereo alone 0, mono alone 1."),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("- scene 2 (seed 123456789; ): stereo 4.5 mm, mono 3.0 mm\n"), std::string::npos) << summary;
  EXPECT_NE(summary.find("- scene 3 (seed 123456789; ): stereo failed, mono 3.0 mm\n"), std::string::npos) << summary;
}

TEST(SuiteStats, SummaryListsWhyGoodResultsWereNotOkAndWhichOffOnesWere) {
  std::vector<SuiteRow> rows(4, sample_row());
  for (int i = 0; i < 4; ++i) rows[i].setting = i + 1;
  for (int i = 0; i < 2; ++i) {  // good, suspect for the same rule at other values
    rows[i].e_t = 0.001, rows[i].e_r = 0.001, rows[i].verdict = "suspect";
    rows[i].check_reasons = "only " + std::to_string(40 + i) + " % agree | the edge score has no clear optimum in rx";
  }
  rows[1].check_reasons = "only 41.5 % agree | a reason may hold a semicolon; like this";
  rows[2].e_t = 0.3, rows[2].e_r = 0.001, rows[2].verdict = "ok";  // off, let through
  rows[2].scene = "wood on bricks";
  rows[3].e_t = 0.001, rows[3].e_r = 0.001, rows[3].verdict = "ok";
  const std::string summary = suite_summary_markdown(rows);
  EXPECT_NE(summary.find("- 2 x only # % agree\n"), std::string::npos) << summary;
  EXPECT_NE(summary.find("- 1 x a reason may hold a semicolon; like this\n"), std::string::npos) << summary;
  EXPECT_NE(summary.find("- 1 x the edge score has no clear optimum in rx\n"), std::string::npos) << summary;
  EXPECT_NE(summary.find("called ok:\n\n- " + rows[2].cell_key() + ": 300 mm"), std::string::npos) << summary;
  EXPECT_NE(summary.find("(wood on bricks)"), std::string::npos) << summary;
}

TEST(SuiteStats, PosesSummaryCountsCoverageAndMovingFramesPerP) {
  std::vector<SuiteRow> rows;
  for (int setting = 1; setting <= 2; ++setting)
    for (int p : {1, 3}) {
      SuiteRow row;
      row.experiment = "poses";
      row.setting = setting;
      row.lidar = "vlp16";
      row.preset = "default";
      row.frames = p == 1 ? 10 : 34;
      row.success = true;
      row.e_t = p == 1 ? 0.004 : 0.001;
      row.e_r = (p == 1 ? 0.1 : 0.02) * M_PI / 180.0;
      // Setting 2's P = 3 run: a moving frame entered a pose, two DoF not covered.
      const bool bad = setting == 2 && p == 3;
      row.scene = "poses=" + std::to_string(p) + " drawn=" + std::to_string(p) + " found=" + std::to_string(p) +
                  " used=" + std::to_string(p) + " moving_in_poses=" + (bad ? "1" : "0") +
                  " covered=" + (bad ? "4" : "6") + " valid=1";
      rows.push_back(row);
    }
  const std::string summary = suite_summary_markdown(rows);
  EXPECT_NE(summary.find("## poses"), std::string::npos) << summary;
  // P = 3: 10 of 12 DoF covered (83 %), one of two runs wholly, one moving frame in a pose.
  EXPECT_NE(summary.find("| default | 3 | 2 | 100 % | 3.00 | 1.00 | 1.00 | 0.020 | 0.020 | 83 % | 50 % | 1 |"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("P = 3 has a smaller e_r than P = 1 in 2 of 2 recordings"), std::string::npos) << summary;
}

}  // namespace
}  // namespace l2s::sim
