// The Calibrator's scene check on injected faults (issue 11) and its
// labelling on any mounting (issue 8): a good calibration is ok; mirrored
// camera labels are turned back by the scene; a scene that cannot tell
// fails as ambiguous instead of guessing; a wrong target size, swapped
// images and a lidar shifted in time against the images never come back
// ok with a wrong transform; a rolled rig and an upside-down lidar
// calibrate with the right labels.

#include <l2s/calibrator.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/simulation.hpp>

#include "support/rolled_rig.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

namespace l2s {
namespace {

using Verdict = CalibrationCheck::Verdict;
constexpr int kFrames = 3;

sim::SimulationConfig setting(int index, std::uint64_t seed) {
  auto config = sim::SimulationConfig::paper(index, "vlp16");
  config.frames = kFrames;
  config.seed = seed;
  return config;
}

// Setting 1: a box beside the board, a textured wall behind it.
const sim::DatasetSimulator& simulator() {
  static const sim::DatasetSimulator instance(setting(1, 51));
  return instance;
}

const std::vector<sim::SimulatedFrame>& frames() {
  static const std::vector<sim::SimulatedFrame> all = [] {
    std::vector<sim::SimulatedFrame> out;
    for (int i = 0; i < kFrames; ++i) out.push_back(simulator().frame(i));
    return out;
  }();
  return all;
}

bool accurate(const Calibrator::Result& result, const Eigen::Isometry3d& truth) {
  const PoseError error = pose_error(result.T_lidar_camera, truth);
  return error.translation <= 0.02 && error.rotation <= 0.5 * M_PI / 180;
}

std::string explain(const Calibrator::Result& result) {
  return result.found ? describe(result.quality) : "no result: " + result.reason;
}

Calibrator::Result calibrate(const Target& target, bool swap_images = false,
                             const std::vector<LidarCloud>* sweeps = nullptr) {
  Calibrator calibrator(simulator().cameras(), target);
  for (int i = 0; i < kFrames; ++i) {
    const auto& frame = frames()[i];
    const LidarCloud& sweep = sweeps ? (*sweeps)[i] : frame.lidar;
    if (swap_images)
      calibrator.add(sweep, frame.right, frame.left);
    else
      calibrator.add(sweep, frame.left, frame.right);
  }
  return calibrator.result();
}

TEST(CalibratorCheck, GoodCalibrationIsOkAndWritesItsQuality) {
  const auto result = calibrate(simulator().config().target);
  ASSERT_TRUE(result.found) << result.reason;
  ASSERT_TRUE(result.checked);
  EXPECT_TRUE(accurate(result, simulator().T_lidar_camera()));
  EXPECT_EQ(result.quality.verdict, Verdict::Ok) << explain(result);
  EXPECT_EQ(result.labels_turned, 0);
  EXPECT_TRUE(result.notes.empty());

  test::TempDir dir;
  io::write_calibration_result(dir.file("result.yaml"), result);
  const YAML::Node quality = YAML::LoadFile(dir.file("result.yaml"))["quality"];
  ASSERT_TRUE(quality.IsMap());
  EXPECT_EQ(quality["verdict"].as<std::string>(), "ok");
  EXPECT_TRUE(quality["peaks"]["ry_deg"]["width"]);
  EXPECT_EQ(quality["alternatives"].size(), 1u);
}

// The check on the frames the calibrator kept, for transforms off the truth
// by 1 deg about one camera axis or 2 cm along one, each on its own.
TEST(CalibratorCheck, TransformOneDegreeOrTwoCentimetresOffIsNotOk) {
  Calibrator calibrator(simulator().cameras(), simulator().config().target);
  for (const auto& frame : frames()) calibrator.add(frame.lidar, frame.left, frame.right);
  const CalibrationCheck check(calibrator.cameras(), calibrator.target(), calibrator.params().check);
  const Eigen::Isometry3d truth = simulator().T_lidar_camera();
  const auto truth_report = check.check(calibrator.check_frames(), truth);
  EXPECT_EQ(truth_report.verdict, Verdict::Ok) << describe(truth_report);
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Isometry3d turned = truth;  // p_lidar = T p_camera: a turn about a camera axis acts on the right
    turned.linear() = truth.linear() * Eigen::AngleAxisd(M_PI / 180, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
    const auto turned_report = check.check(calibrator.check_frames(), turned);
    EXPECT_NE(turned_report.verdict, Verdict::Ok) << "1 deg about axis " << axis << "\n" << describe(turned_report);

    Eigen::Isometry3d shifted = truth;
    shifted.translation() += 0.02 * (truth.linear() * Eigen::Vector3d::Unit(axis));
    const auto shifted_report = check.check(calibrator.check_frames(), shifted);
    EXPECT_NE(shifted_report.verdict, Verdict::Ok) << "2 cm along axis " << axis << "\n" << describe(shifted_report);
  }
}

/// Camera branch reports of every frame, their labels turned by 180 deg when
/// `turned`: a camera that sees the board upside down against the lidar.
std::vector<BranchReport> camera_reports(const Calibrator& calibrator, bool turned, bool keep_observation) {
  std::vector<BranchReport> reports;
  const HolePermutation half = hole_symmetries(simulator().config().target)[1].permutation;
  for (const auto& frame : frames()) {
    BranchReport report = calibrator.camera_branch(frame.left, frame.right);
    if (turned) report.centers = relabel(report.centers, half);
    if (!keep_observation) report.observation.reset();
    reports.push_back(report);
  }
  return reports;
}

TEST(CalibratorCheck, MirroredCameraLabelsAreTurnedBackByTheScene) {
  Calibrator calibrator(simulator().cameras(), simulator().config().target);
  const auto reports = camera_reports(calibrator, true, true);
  for (int i = 0; i < kFrames; ++i) calibrator.add(frames()[i].lidar, reports[i]);
  const auto result = calibrator.result();
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.labels_turned, 180);
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("turned by 180 deg"), std::string::npos) << result.notes[0];
  EXPECT_TRUE(accurate(result, simulator().T_lidar_camera())) << explain(result);
  EXPECT_EQ(result.quality.verdict, Verdict::Ok) << explain(result);
}

/// Nothing but the board: its returns alone, no image edges or stereo
/// depth, the camera's labels turned when `turned`.
Calibrator::Result calibrate_board_only(bool turned, double upright_deg = 30.0) {
  // The board centre in the lidar frame: the simulator's board pose is in the camera body frame.
  const Eigen::Isometry3d T_lidar_cambody = simulator().config().setting.T_cambody_lidar().inverse();
  const Eigen::Vector3d centre = T_lidar_cambody * simulator().board_pose().T_cambody_board().translation();
  Calibrator::Params params = Calibrator::Params::preset("default");
  params.check.upright_deg = upright_deg;
  Calibrator calibrator(simulator().cameras(), simulator().config().target, params);
  const auto reports = camera_reports(calibrator, turned, false);
  for (int i = 0; i < kFrames; ++i) {
    LidarCloud board_only;
    const LidarCloud& sweep = frames()[i].lidar;
    for (std::size_t k = 0; k < sweep.size(); ++k)
      if ((sweep.points[k] - centre).norm() < 1.0) {
        board_only.points.push_back(sweep.points[k]);
        board_only.ring.push_back(sweep.ring[k]);
      }
    calibrator.add(board_only, reports[i]);
  }
  return calibrator.result();
}

// The turned fit explains a board alone as well as the other, and stands
// the lidar upside down against the camera: a clear error.
TEST(CalibratorCheck, SceneThatCannotTellFailsAsAmbiguous) {
  const auto result = calibrate_board_only(true);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.labels_turned, 0);
  EXPECT_EQ(result.quality.verdict, Verdict::Failed) << explain(result);
  EXPECT_TRUE(result.quality.ambiguous) << explain(result);
  EXPECT_FALSE(result.quality.upright_only) << explain(result);
  ASSERT_FALSE(result.quality.reasons.empty());
  EXPECT_NE(result.quality.reasons[0].find("ambiguous"), std::string::npos) << result.quality.reasons[0];
}

// The same board with labels that agree: the scene still cannot tell, but
// only this fit stands both sensors upright, so the result is suspect (with
// that reason), not failed; with the mounting prior off it fails.
TEST(CalibratorCheck, SceneThatCannotTellIsSuspectWhenOnlyOneFitStandsTheSensorsUpright) {
  const auto result = calibrate_board_only(false);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_TRUE(accurate(result, simulator().T_lidar_camera())) << explain(result);
  EXPECT_TRUE(result.quality.ambiguous) << explain(result);
  EXPECT_TRUE(result.quality.upright_only) << explain(result);
  EXPECT_EQ(result.quality.verdict, Verdict::Suspect) << explain(result);
  bool told = false;
  for (const auto& reason : result.quality.reasons) told |= reason.find("upright") != std::string::npos;
  EXPECT_TRUE(told) << explain(result);

  const auto without_prior = calibrate_board_only(false, 0.0);
  EXPECT_EQ(without_prior.quality.verdict, Verdict::Failed) << explain(without_prior);
}

// A target.yaml 3 % larger or smaller than the board: the camera places the
// board 3 % too far or near, the fit follows, and the lidar board lies off
// the stereo plane.
TEST(CalibratorCheck, WrongTargetSizeIsNeverOkWhenTheResultIsOff) {
  for (const double scale : {0.97, 1.03}) {
    Target target = simulator().config().target;
    target.board_width *= scale;
    target.board_height *= scale;
    target.hole_radius *= scale;
    target.hole_spacing_x *= scale;
    target.hole_spacing_y *= scale;
    const auto result = calibrate(target);
    // The holes' radius and spacing are within the finders' tolerances, so
    // both branches find the board: the fault shows only in the result.
    ASSERT_TRUE(result.found) << "scale " << scale << ": " << result.reason;
    EXPECT_FALSE(accurate(result, simulator().T_lidar_camera())) << "scale " << scale;
    EXPECT_NE(result.quality.verdict, Verdict::Ok) << "scale " << scale << "\n" << explain(result);
  }
}

// Left and right images swapped: every disparity changes sign, stereo
// matching finds no board, and no result is given (let alone an ok one).
TEST(CalibratorCheck, SwappedImagesGiveNoResult) {
  const auto result = calibrate(simulator().config().target, true);
  EXPECT_FALSE(result.found) << explain(result);
  EXPECT_EQ(result.camera_frames, 0) << explain(result);
}

// Unsynchronised sensors: in every frame the board stood 5 cm to the side and
// turned by 3 deg when the lidar swept it. The fit follows the board; the
// scene around it does not.
TEST(CalibratorCheck, LidarShiftedInTimeAgainstTheImagesIsCaught) {
  auto moved = simulator().config();
  moved.board_pose = simulator().board_pose();
  moved.board_pose->y += 0.05;
  moved.board_pose->yaw += 0.05;
  const sim::DatasetSimulator other(moved);
  std::vector<LidarCloud> sweeps;
  for (int i = 0; i < kFrames; ++i) sweeps.push_back(other.sweep(i));
  const auto result = calibrate(simulator().config().target, false, &sweeps);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_FALSE(accurate(result, simulator().T_lidar_camera()));
  // Seen by the depth tilt off the board (about 2.9 deg here): suspect or failed, never ok.
  EXPECT_NE(result.quality.verdict, Verdict::Ok) << explain(result);
}

// A camera detection the fit left out must not judge the result: of random
// scene 399770965's two camera detections one took a tile wall 6.3 m away
// for the board; the fit kept the other (6.7 mm off), and the check, which
// measured the lidar board against both, called it failed ("board 2.7 m
// off"). Here frame 1's camera board is put 2.2 times as far.
Calibrator::Result calibrate_with_far_camera_board_in_frame_1(int frame_count) {
  Calibrator calibrator(simulator().cameras(), simulator().config().target);
  for (int i = 0; i < frame_count; ++i) {
    const auto& frame = frames()[i];
    BranchReport camera = calibrator.camera_branch(frame.left, frame.right);
    EXPECT_TRUE(camera.found && camera.observation && camera.observation->T_camera_board) << camera.reason;
    if (i == 1 && camera.observation && camera.observation->T_camera_board) {
      for (auto& center : camera.centers) center *= 2.2;
      auto far = std::make_shared<CameraObservation>(*camera.observation);
      far->T_camera_board->translation() *= 2.2;
      far->stereo_plane.reset();
      camera.observation = std::move(far);
    }
    calibrator.add(frame.lidar, camera);
  }
  return calibrator.result();
}

TEST(CalibratorCheck, CameraDetectionTheFitLeftOutDoesNotJudgeTheResult) {
  // Two of three detections agree: a clear consensus, the third is wrong.
  const auto result = calibrate_with_far_camera_board_in_frame_1(3);
  ASSERT_TRUE(result.found) << result.reason;
  ASSERT_EQ(result.poses.size(), 1u);
  EXPECT_EQ(result.poses[0].camera_outlier_frames, std::vector<int>{1});
  EXPECT_TRUE(result.poses[0].lidar_outlier_frames.empty());
  EXPECT_TRUE(accurate(result, simulator().T_lidar_camera()));
  EXPECT_EQ(result.quality.board_frames, 2) << explain(result);
  EXPECT_EQ(result.quality.verdict, Verdict::Ok) << explain(result);

  // One against one: the fit kept the first, the board agrees with it, and
  // nothing says the other was the wrong one: suspect, not failed.
  const auto split = calibrate_with_far_camera_board_in_frame_1(2);
  ASSERT_TRUE(split.found) << split.reason;
  EXPECT_TRUE(accurate(split, simulator().T_lidar_camera()));
  EXPECT_EQ(split.quality.board_frames, 1) << explain(split);
  EXPECT_LT(std::abs(split.quality.scores.plane_offset), 0.005) << explain(split);
  EXPECT_EQ(split.quality.verdict, Verdict::Suspect) << explain(split);
  ASSERT_EQ(split.quality.reasons.size(), 1u) << explain(split);
  EXPECT_NE(split.quality.reasons[0].find("camera's detections of pose 0 disagree"), std::string::npos);
}

Calibrator::Result calibrate_simulation(const sim::SimulationConfig& config, const sim::DatasetSimulator& simulator) {
  Calibrator calibrator(simulator.cameras(), config.target);
  for (int i = 0; i < config.frames; ++i) {
    const auto frame = simulator.frame(i);
    calibrator.add(frame.lidar, frame.left, frame.right);
  }
  return calibrator.result();
}

// A stereo rig rolled by 90 or 180 deg about its optical axis against the lidar.
class CalibratorRolledRig : public ::testing::TestWithParam<int> {};

TEST_P(CalibratorRolledRig, CalibratesWithTheRightLabels) {
  const auto base = setting(2, 60 + GetParam());
  const sim::BoardPose pose = sim::DatasetSimulator(base).board_pose();
  const auto config = test::rolled_rig(base, pose, GetParam());
  const sim::DatasetSimulator rolled(config);
  const auto result = calibrate_simulation(config, rolled);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_TRUE(accurate(result, rolled.T_lidar_camera())) << explain(result);
  EXPECT_EQ(result.quality.verdict, Verdict::Ok) << explain(result);
  if (GetParam() == 180) {
    EXPECT_EQ(result.labels_turned, 180);
  }
}

INSTANTIATE_TEST_SUITE_P(Roll, CalibratorRolledRig, ::testing::Values(90, 180),
                         [](const auto& info) { return "Degrees" + std::to_string(info.param); });

TEST(CalibratorCheck, UpsideDownLidarCalibratesWithTheRightLabels) {
  auto config = setting(2, 70);
  config.setting_index = 0;
  config.setting.roll += M_PI;
  const sim::DatasetSimulator simulator(config);
  const auto result = calibrate_simulation(config, simulator);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.labels_turned, 180);
  EXPECT_TRUE(accurate(result, simulator.T_lidar_camera())) << explain(result);
  EXPECT_EQ(result.quality.verdict, Verdict::Ok) << explain(result);
}

}  // namespace
}  // namespace l2s
