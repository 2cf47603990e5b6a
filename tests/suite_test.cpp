// The pure parts of `l2s suite`: the plan (cells, groups, seeds), results.csv
// round trip and resume, thresholds (statistics and summary.md:
// suite_summary_test.cpp). The runner is exercised by
// `l2s suite --quick` in CI and by one small group here.

#include <l2s/sim/suite.hpp>
#include <l2s/sim/suite_results.hpp>

#include <l2s/error.hpp>

#include "support/suite_rows.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

namespace l2s::sim {
namespace {

namespace fs = std::filesystem;

std::size_t count_cells(const std::vector<SuiteGroup>& plan) {
  std::size_t n = 0;
  for (const auto& group : plan) n += group.cells.size();
  return n;
}

SuiteOptions options_for(const std::string& experiment, int repeats) {
  SuiteOptions options;
  options.experiments = {experiment};
  options.repeats = repeats;
  return options;
}

std::string temp_file(const std::string& name) {
  const char* root = std::getenv("L2S_TEST_TMP");
  const fs::path folder = fs::path(root ? root : fs::temp_directory_path().string()) / "suite_test";
  fs::create_directories(folder);
  return (folder / name).string();
}

// The row of a cell that ran, with sample_row()'s outcome.
SuiteRow finished(const SuiteCell& cell) {
  const SuiteRow sample = sample_row();
  SuiteRow row = SuiteRow::of(cell);
  row.success = sample.success;
  row.e_t = sample.e_t;
  row.e_r = sample.e_r;
  row.lidar_frames = sample.lidar_frames;
  row.camera_frames = sample.camera_frames;
  row.wall_s = sample.wall_s;
  return row;
}

TEST(SuitePlan, CountsCellsPerExperiment) {
  const int r = 3;
  const auto frames = make_suite_plan(options_for("frames", r));
  EXPECT_EQ(frames.size(), 9u * r);
  EXPECT_EQ(count_cells(frames), 9u * r * 2);  // x presets
  for (const auto& group : frames)
    for (const auto& cell : group.cells) {
      EXPECT_TRUE(cell.every_frame);
      EXPECT_EQ(cell.rows(), 40);
    }
  const auto noise = make_suite_plan(options_for("noise", r));
  EXPECT_EQ(noise.size(), 4u * 9 * r);
  EXPECT_EQ(count_cells(noise), 4u * 9 * r * 2);
  const auto lidars = make_suite_plan(options_for("lidars", r));
  EXPECT_EQ(lidars.size(), 9u * r);
  EXPECT_EQ(count_cells(lidars), 9u * r * 3 * 2);  // all lidars of a group share its frames
  for (const auto& group : lidars)
    for (const auto& cell : group.cells) EXPECT_EQ(cell.rows(), 1);

  SuiteOptions one_preset = options_for("noise", 1);
  one_preset.presets = {"default"};
  EXPECT_EQ(count_cells(make_suite_plan(one_preset)), 36u);
  EXPECT_EQ(count_cells(make_suite_plan(options_for("quick", 1))), 3u * 2);
}

TEST(SuitePlan, SeedsAreDeterministicAndDistinct) {
  SuiteOptions options;
  options.repeats = 4;
  const auto plan = make_suite_plan(options);
  const auto again = make_suite_plan(options);
  std::set<std::uint64_t> seeds;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(plan[i].seed, again[i].seed);
    seeds.insert(plan[i].seed);
    for (const auto& cell : plan[i].cells) EXPECT_EQ(cell.seed, plan[i].seed);
  }
  EXPECT_EQ(seeds.size(), plan.size()) << "every group needs its own seed";
  options.seed = 2;
  EXPECT_NE(make_suite_plan(options)[0].seed, plan[0].seed);
  EXPECT_NE(suite_seed(1, "noise", 1, 1.0, 0), suite_seed(1, "lidars", 1, 1.0, 0));
  EXPECT_NE(suite_seed(1, "noise", 1, 1.0, 0), suite_seed(1, "noise", 1, 2.0, 0));
}

TEST(SuitePlan, RejectsUnknownNames) {
  EXPECT_THROW(make_suite_plan(options_for("weather", 1)), ParamError);
  SuiteOptions options;
  options.presets = {"fast"};
  EXPECT_THROW(make_suite_plan(options), ParamError);
  EXPECT_THROW(make_suite_plan(options_for("noise", 0)), ParamError);
  // The left camera alone needs the markers only random scenes draw.
  options = options_for("noise", 1);
  options.presets = {"default", "mono"};
  EXPECT_THROW(make_suite_plan(options), ParamError);
  options = options_for("scenes", 1);
  options.presets = {"default", "mono"};
  EXPECT_NO_THROW(make_suite_plan(options));
}

TEST(SuiteCsv, LineRoundTripKeepsEveryField) {
  SuiteRow row = sample_row();
  row.success = false;
  row.reason = "too few frames: lidar 3, camera \"0\" of 30\nsecond line";
  row.e_t = row.e_r = std::nan("");
  const SuiteRow back = parse_csv_line(to_csv_line(row));
  EXPECT_EQ(back.experiment, row.experiment);
  EXPECT_EQ(back.setting, row.setting);
  EXPECT_EQ(back.noise_k, row.noise_k);
  EXPECT_EQ(back.seed, row.seed);
  EXPECT_EQ(back.repetition, row.repetition);
  EXPECT_FALSE(back.success);
  EXPECT_EQ(back.reason, "too few frames: lidar 3, camera \"0\" of 30 second line");
  EXPECT_TRUE(std::isnan(back.e_t));
  EXPECT_EQ(back.cell_key(), row.cell_key());
  EXPECT_TRUE(back.scene.empty());

  row.scene = "800x600 95.0deg B=0.235m rectified | wood on plain 1.93m, colour | avia (quirks)";
  row.verdict = "suspect";
  EXPECT_EQ(parse_csv_line(to_csv_line(row)).scene, row.scene);
  EXPECT_EQ(parse_csv_line(to_csv_line(row)).verdict, "suspect");
  EXPECT_EQ(parse_csv_line(to_csv_line(row)).covered, -1);
  row.covered = 5;
  row.check_reasons = "only 55 % of the lidar returns agree, \"so\" | the edge score has no clear optimum in rx";
  const std::string line = to_csv_line(row);
  EXPECT_EQ(parse_csv_line(line).covered, 5);
  EXPECT_EQ(parse_csv_line(line).check_reasons, row.check_reasons);
  EXPECT_TRUE(std::isnan(parse_csv_line(line).e_lidar_centres));
  row.e_lidar_centres = 0.0021;
  row.e_camera_centres = 0.0123;
  EXPECT_EQ(parse_csv_line(to_csv_line(row)).e_lidar_centres, 0.0021);
  EXPECT_EQ(parse_csv_line(to_csv_line(row)).e_camera_centres, 0.0123);
  EXPECT_TRUE(std::isnan(parse_csv_line(to_csv_line(row)).bound_t));
  row.bound_t = 0.034;
  row.bound_r = 0.0061;
  EXPECT_EQ(parse_csv_line(to_csv_line(row)).bound_t, 0.034);
  EXPECT_EQ(parse_csv_line(to_csv_line(row)).bound_r, 0.0061);
  EXPECT_TRUE(std::isnan(parse_csv_line(to_csv_line(row)).roll));
  row.face = "noise-print";
  row.markers = "DICT_5X5_100";
  row.roll = -0.5 * M_PI;
  row.lens = "raw plumb_bob";
  const SuiteRow drawn = parse_csv_line(to_csv_line(row));
  EXPECT_EQ(drawn.face, "noise-print");
  EXPECT_EQ(drawn.markers, "DICT_5X5_100");
  EXPECT_NEAR(drawn.roll, -0.5 * M_PI, 1e-12);
  EXPECT_EQ(drawn.lens, "raw plumb_bob");
  EXPECT_TRUE(parse_csv_line(to_csv_line(row).substr(0, to_csv_line(row).rfind(",noise-print"))).face.empty());
  // results.csv of earlier releases have no stated bounds, before that no
  // centre errors, before that no check_reasons column, and before that no
  // covered column: they still read.
  const std::string without_bounds = to_csv_line(row).substr(0, to_csv_line(row).rfind(",0.034"));
  EXPECT_EQ(parse_csv_line(without_bounds).e_camera_centres, 0.0123);
  EXPECT_TRUE(std::isnan(parse_csv_line(without_bounds).bound_r));
  EXPECT_TRUE(std::isnan(parse_csv_line(line.substr(0, line.rfind(",nan,nan,nan,nan"))).e_camera_centres));
  const std::string without_reasons = line.substr(0, line.rfind(",\""));
  EXPECT_EQ(parse_csv_line(without_reasons).covered, 5);
  EXPECT_TRUE(parse_csv_line(without_reasons).check_reasons.empty());
  const SuiteRow legacy = parse_csv_line(without_reasons.substr(0, without_reasons.rfind(',')));
  EXPECT_EQ(legacy.verdict, "suspect");
  EXPECT_EQ(legacy.covered, -1);

  const SuiteRow good = parse_csv_line(to_csv_line(sample_row()));
  EXPECT_EQ(good.e_t, sample_row().e_t) << "errors are written exactly";
  EXPECT_EQ(good.e_r, sample_row().e_r);
  EXPECT_THROW(parse_csv_line("noise,4,vlp16"), Error);
}

TEST(SuiteCsv, ResumeSkipsFinishedCellsAndDropsPartialOnes) {
  const auto plan = make_suite_plan(options_for("quick", 1));  // 3 groups x 2 presets, 1 row each
  std::vector<SuiteRow> rows;
  for (const auto& cell : plan[0].cells) {
    rows.push_back(finished(cell));
  }
  const std::string path = temp_file("results.csv");
  write_suite_csv(path, rows);
  // An interrupted append: half a line without its newline.
  const std::string half = to_csv_line(rows[0]).substr(0, 20);
  { std::ofstream(path, std::ios::app) << half; }

  const SuiteCsv csv = read_suite_csv(path);
  EXPECT_TRUE(csv.trimmed);
  ASSERT_EQ(csv.rows.size(), rows.size());
  const SuiteResume resume = resume_suite(plan, csv.rows);
  EXPECT_EQ(resume.done.size(), 2u);
  EXPECT_EQ(resume.kept.size(), 2u);
  EXPECT_EQ(resume.dropped, 0u);
  EXPECT_TRUE(resume.done.count(plan[0].cells[0].key()));
  EXPECT_FALSE(resume.done.count(plan[1].cells[0].key()));

  // A streaming cell with only some of its evaluations is run again.
  const auto frames_plan = make_suite_plan(options_for("frames", 1));
  const SuiteCell& cell = frames_plan[0].cells[0];
  std::vector<SuiteRow> partial;
  for (int n = 1; n <= 5; ++n) {
    SuiteRow row = finished(cell);
    row.frames = n;
    partial.push_back(row);
  }
  const SuiteResume again = resume_suite(frames_plan, partial);
  EXPECT_TRUE(again.done.empty());
  EXPECT_EQ(again.dropped, 5u);

  // Rows of another --seed are refused, not mixed.
  partial[0].seed += 1;
  EXPECT_THROW(resume_suite(frames_plan, partial), Error);
  const std::string other = temp_file("other.csv");
  test::write_text(other, "a,b\n1,2\n");
  EXPECT_THROW(read_suite_csv(other), FileError) << "a CSV of another tool is not overwritten";
}

TEST(SuitePlan, ScenesAreCountedNotRepeatedAndDrawTheirLidar) {
  SuiteOptions options = options_for("scenes", 3);
  options.scene_count = 5;
  options.scene_frames = 7;
  const auto plan = make_suite_plan(options);
  ASSERT_EQ(plan.size(), 5u) << "one group per scene, repeats do not apply";
  std::set<std::uint64_t> seeds;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(plan[i].setting, static_cast<int>(i) + 1);
    EXPECT_EQ(plan[i].frames, 7);
    ASSERT_EQ(plan[i].cells.size(), 2u);  // both presets
    EXPECT_EQ(plan[i].cells[0].lidar, "random");
    EXPECT_EQ(plan[i].boards, BoardDraw::All);
    seeds.insert(plan[i].seed);
  }
  EXPECT_EQ(seeds.size(), 5u);
  options.scene_boards = BoardDraw::Classic;
  for (const auto& group : make_suite_plan(options)) EXPECT_EQ(group.boards, BoardDraw::Classic);
  options.scene_count = 0;
  EXPECT_THROW(make_suite_plan(options), ParamError);
}

TEST(SuiteThresholds, ScenesArePooledAndHaveTheirOwnLimits) {
  const std::string path = temp_file("scene_thresholds.yaml");
  test::write_text(path,
                   "presets:\n  default: {min_success_rate: 1.0, max_e_t_mm: 1.0, max_e_r_deg: 1}\n"
                   "experiments:\n  scenes:\n    default: {min_success_rate: 0.6, max_e_t_mm: 10, max_e_r_deg: 1}\n");
  const SuiteThresholds thresholds = read_suite_thresholds(path);
  std::vector<SuiteRow> rows(3, sample_row());
  for (int i = 0; i < 3; ++i) {
    rows[i].experiment = "scenes";
    rows[i].lidar = "random";
    rows[i].preset = "default";
    rows[i].setting = i + 1;
    rows[i].e_t = 0.004;  // above the presets' 1 mm, within the scenes' 10 mm
    rows[i].e_r = 0.001;
  }
  rows[2].success = false;  // 2 of 3 found: above 0.6 when the scenes are one distribution
  EXPECT_TRUE(check_suite_thresholds(rows, thresholds).empty());
  rows[1].success = false;  // 1 of 3
  const auto violations = check_suite_thresholds(rows, thresholds);
  ASSERT_EQ(violations.size(), 1u);
  EXPECT_NE(violations[0].find("success rate 0.33"), std::string::npos) << violations[0];
}

TEST(SuiteThresholds, ReportsCellsOutsideTheLimits) {
  const std::string path = temp_file("thresholds.yaml");
  test::write_text(path,
                   "presets:\n  paper: {min_success_rate: 1.0, max_e_t_mm: 1.0, max_e_r_deg: 30}\n");
  const SuiteThresholds thresholds = read_suite_thresholds(path);
  ASSERT_EQ(thresholds.presets.size(), 1u);
  EXPECT_DOUBLE_EQ(thresholds.presets[0].second.max_e_t, 0.001);

  std::vector<SuiteRow> rows(1, sample_row());  // e_t 1.23 mm > 1 mm
  EXPECT_EQ(check_suite_thresholds(rows, thresholds).size(), 1u);
  rows[0].e_t = 0.0005;
  EXPECT_TRUE(check_suite_thresholds(rows, thresholds).empty());
  rows[0].success = false;
  EXPECT_EQ(check_suite_thresholds(rows, thresholds).size(), 1u);
  rows[0].preset = "default";  // no limits given for it
  EXPECT_TRUE(check_suite_thresholds(rows, thresholds).empty());

  test::write_text(path, "presets:\n  paper: {max_e_t_mm: 1.0}\n");
  EXPECT_THROW(read_suite_thresholds(path), FileError);
}

TEST(SuiteRunner, StreamingCellGivesOneRowPerFrameAndSharesTheFrames) {
  SuiteGroup group;
  group.experiment = "frames";
  group.setting = 8;
  group.frames = 2;
  group.seed = 5;
  for (const char* preset : {"default", "paper"})
    group.cells.push_back({"frames", 8, "vlp16", 1.0, 2, preset, 0, 5, true});
  int frames_seen = 0;
  const auto rows = run_suite_group(group, group.cells, 0, [&] { ++frames_seen; });
  EXPECT_EQ(frames_seen, 2);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].frames, 1);
  EXPECT_EQ(rows[1].frames, 2);
  EXPECT_EQ(rows[2].preset, "paper");
  // Every row calibrates; bounds twice what each measured (default after one
  // and two frames: 4.9 / 4.4 mm, 0.16 / 0.21 deg; paper: 1.8 / 2.5 mm,
  // 0.04 / 0.08 deg).
  const double max_e_t[4] = {0.0098, 0.0088, 0.0036, 0.0051};  // [m]
  const double max_e_r[4] = {0.0056, 0.0075, 0.0014, 0.0029};  // [rad]
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    EXPECT_EQ(row.seed, 5u);
    ASSERT_TRUE(row.success) << row.preset << " after " << row.frames << ": " << row.reason;
    EXPECT_LT(row.e_t, max_e_t[i]) << row.preset << " after " << row.frames;
    EXPECT_LT(row.e_r, max_e_r[i]) << row.preset << " after " << row.frames;
  }

  // The same group again gives the same numbers.
  const auto again = run_suite_group(group, {group.cells[1]}, 1);
  ASSERT_EQ(again.size(), 2u);
  EXPECT_EQ(again[1].e_t, rows[3].e_t);
  EXPECT_EQ(again[1].e_r, rows[3].e_r);
}

}  // namespace
}  // namespace l2s::sim

namespace l2s::sim {
namespace {

TEST(SuitePlan, PosesExperimentIsOneRecordingPerSettingWithFourEvaluations) {
  for (const char* experiment : {"poses", "mono", "lidar-pair"}) {
    SuiteOptions options;
    options.experiments = {experiment};
    options.presets = {"default"};
    options.repeats = 2;
    const std::vector<SuiteGroup> plan = make_suite_plan(options);
    ASSERT_EQ(plan.size(), 18u) << experiment;
    for (const SuiteGroup& group : plan) {
      EXPECT_EQ(group.frames, 5 * 10 + 4 * 2);  // five poses of 10 frames, 2 moving frames between
      ASSERT_EQ(group.cells.size(), 1u);
      EXPECT_EQ(group.cells[0].lidar, "vlp16");
      EXPECT_EQ(group.cells[0].rows(), 4) << experiment;
    }
  }
}

/// The first group of a pose experiment's plan (setting 1, seed of the plan), default preset.
SuiteGroup first_pose_group(const std::string& experiment) {
  SuiteOptions options;
  options.experiments = {experiment};
  options.presets = {"default"};
  options.repeats = 1;
  return make_suite_plan(options).front();
}

/// The four evaluations of one recording: after 1, 2, 3 and 5 poses, every
/// one calibrated, no moving frame in a pose, within `max_e_t` / `max_e_r`.
void expect_pose_rows(const std::vector<SuiteRow>& rows, double max_e_t, double max_e_r) {
  ASSERT_EQ(rows.size(), 4u);
  const int asked[4] = {1, 2, 3, 5};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const SuiteRow& row = rows[i];
    EXPECT_TRUE(row.success) << row.reason;
    EXPECT_NE(row.scene.find("poses=" + std::to_string(asked[i]) + " "), std::string::npos) << row.scene;
    EXPECT_NE(row.scene.find("moving_in_poses=0"), std::string::npos) << row.scene;
    EXPECT_LT(row.e_t, max_e_t) << row.scene;
    EXPECT_LT(row.e_r, max_e_r) << row.scene;
    EXPECT_GT(row.lidar_frames, 0);
    EXPECT_GT(row.camera_frames, 0);  // lidar-pair: the second lidar's detections
    EXPECT_EQ(row.verdict, "ok") << row.check_reasons;
    if (i > 0) {
      EXPECT_GT(row.frames, rows[i - 1].frames);
    }
  }
}

// A scene that keeps a solid-state lidar's returns as one accumulated cloud
// (4 s of a Mid-360-like lidar, the whole scene) is detected once and pairs
// with every frame. Bounds about twice what it measured with 10 frames:
// 8.7 mm, 0.20 deg, hole centres 3.5 mm.
TEST(SuiteRunner, AScenesDrawOfAnAccumulatedCloudCalibrates) {
  SuiteGroup group;
  group.experiment = "scenes";
  group.frames = 10;
  group.seed = 664592208;
  group.cells.push_back({"scenes", 1, "random", 1.0, 10, "default", 0, group.seed, false});
  const auto rows = run_suite_group(group, group.cells, 0);
  ASSERT_EQ(rows.size(), 1u);
  const SuiteRow& row = rows[0];
  EXPECT_NE(row.scene.find("accumulated"), std::string::npos) << row.scene;
  ASSERT_TRUE(row.success) << row.reason;
  EXPECT_EQ(row.lidar_frames, 10) << "the cloud's centres pair with every frame";
  EXPECT_LT(row.e_lidar_centres, 0.005) << row.scene;
  EXPECT_LT(row.e_t, 0.018) << row.scene;
  EXPECT_LT(row.e_r, 0.007) << row.scene;
}

// Bounds about three times what each measured (setting 1, seed of the plan):
// mono 1.2 / 0.6 / 0.5 / 0.4 mm and 0.025 / 0.042 / 0.013 / 0.007 deg.
TEST(SuiteRunner, MonoExperimentCalibratesTheLeftCameraByTheMarkers) {
  const SuiteGroup group = first_pose_group("mono");
  expect_pose_rows(run_suite_group(group, group.cells, 0), 0.004, 0.15 * M_PI / 180.0);
}

// Lidar-pair 1.7 / 0.6 / 1.0 / 1.1 mm and 0.16 / 0.03 / 0.03 / 0.02 deg.
TEST(SuiteRunner, LidarPairExperimentCalibratesTheSecondLidar) {
  const SuiteGroup group = first_pose_group("lidar-pair");
  expect_pose_rows(run_suite_group(group, group.cells, 0), 0.006, 0.4 * M_PI / 180.0);
}

}  // namespace
}  // namespace l2s::sim
