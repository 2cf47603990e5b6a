// The camera branch on rigs and scenes other than the paper's (issue: any
// stereo rig): other focal lengths and baselines, and a board-sized surface
// without holes that the plane stage meets before the board. Frames come from
// the simulator and run through the branch exactly as Calibrator::add runs it.

#include <l2s/calibrator.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/sim/random_scene.hpp>
#include <l2s/sim/simulation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace l2s {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// The true hole centres on the board's front face, left optical frame.
HoleCenters true_centers(const sim::DatasetSimulator& simulator) {
  const Eigen::Isometry3d T_optical_board =
      simulator.config().rig.T_cambody_optical(0).inverse() * simulator.scene().T_cambody_board;
  const auto holes = simulator.config().target.hole_centers();
  HoleCenters out;
  for (int h = 0; h < 4; ++h) out[h] = T_optical_board * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0);
  return out;
}

double centre_error(const HoleCenters& found, const HoleCenters& truth) {
  double worst = 0.0;
  for (int h = 0; h < 4; ++h) worst = std::max(worst, (found[h] - truth[h]).norm());
  return worst;
}

sim::SimulationConfig config_with(const sim::StereoRig& rig, std::uint64_t seed) {
  auto config = sim::SimulationConfig::paper(1, "vlp16");
  config.rig = rig;
  config.frames = 3;
  config.seed = seed;
  return config;
}

/// Every frame of the simulator through the camera branch: found, and the
/// centres within `tolerance` of the truth.
void expect_found_in_every_frame(const sim::DatasetSimulator& simulator, double tolerance) {
  const auto params = Calibrator::Params::preset("default");
  for (int i = 0; i < simulator.config().frames; ++i) {
    const auto frame = simulator.frame(i);
    const CameraInspection in =
        inspect_camera(frame.left, frame.right, simulator.cameras(), simulator.config().target, params);
    ASSERT_TRUE(in.report.found) << "frame " << i << ":\n" << describe(in, params, simulator.cameras());
    EXPECT_LT(centre_error(in.report.centers, true_centers(simulator)), tolerance)
        << "frame " << i << ":\n" << describe(in, params, simulator.cameras());
  }
}

struct RigCase {
  const char* name;
  int width, height;
  double hfov_deg, baseline;
};

class CameraDetectionOnRigs : public ::testing::TestWithParam<RigCase> {};

TEST_P(CameraDetectionOnRigs, FindsTheBoardInEveryFrame) {
  const RigCase& c = GetParam();
  sim::StereoRig rig;
  rig.width = c.width;
  rig.height = c.height;
  rig.horizontal_fov = c.hfov_deg * kDeg;
  rig.baseline = c.baseline;
  const sim::DatasetSimulator simulator(config_with(rig, 11));
  expect_found_in_every_frame(simulator, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Rigs, CameraDetectionOnRigs,
                         ::testing::Values(RigCase{"Fx985Baseline12cm", 1280, 960, 66.0, 0.12},
                                           RigCase{"Wide640x480", 640, 480, 80.0, 0.10},
                                           RigCase{"Baseline40cm1920x1200", 1920, 1200, 60.0, 0.40}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(CameraDetection, ABoardSizedPanelWithoutHolesBeforeTheBoardLoses) {
  // The panel is nearer, so its plane has more stereo points and comes first;
  // it has the board's size but no holes.
  sim::StereoRig rig;
  rig.horizontal_fov = 66.0 * kDeg;
  auto config = config_with(rig, 12);
  config.board_pose = sim::BoardPose{3.5, 0.55, -0.1, 0.15, 0.0, 0.02};
  config.strict_placement = false;
  sim::Box panel;
  panel.T_cambody_box.translation() = Eigen::Vector3d(2.5, -0.85, -0.1);
  panel.half_size = Eigen::Vector3d(0.01, 0.7, 0.5);  // 1.4 x 1.0 m, facing the cameras
  config.layout.extra_clutter.push_back(panel);
  const sim::DatasetSimulator simulator(config);

  auto params = Calibrator::Params::preset("default");
  params.camera_verifier.confident_score = 1.0;  // try every hypothesis: the panel must be tried and lose
  const auto frame = simulator.frame(0);
  const CameraInspection in =
      inspect_camera(frame.left, frame.right, simulator.cameras(), config.target, params);
  ASSERT_TRUE(in.report.found) << describe(in, params, simulator.cameras());
  EXPECT_LT(centre_error(in.report.centers, true_centers(simulator)), 0.01);
  // The panel was a hypothesis too, and lost.
  bool panel_tried = false;
  for (const BoardHypothesis& h : in.hypotheses) {
    const Plane& plane = in.plane->candidates[h.candidate].plane;
    const bool is_panel = std::abs(plane.offset() - 2.5) < 0.3;
    panel_tried |= is_panel;
    EXPECT_FALSE(is_panel && h.chosen) << h.reason;
  }
  EXPECT_TRUE(panel_tried);
  expect_found_in_every_frame(simulator, 0.01);
}

// The coarse pass cuts a board over a plain wall into several patches (paper
// setting 1: the board and pieces of it). Once one of them gave the board's
// holes, the others lie on that board and are skipped, not matched again at
// full resolution: each would cost the region's SGBM and every later stage.
TEST(CameraDetection, PiecesOfABoardAlreadyFoundAreNotTriedAgain) {
  auto config = sim::SimulationConfig::paper(1, "vlp16");
  config.frames = 1;
  config.seed = 11;
  const sim::DatasetSimulator simulator(config);
  auto params = Calibrator::Params::preset("default");
  // The pieces (priors ~0.1 against the board's 0.84) would not be tried at
  // all after the board; this tests what happens when they are.
  params.camera_verifier.challenger_prior = 0.0;
  const auto frame = simulator.frame(0);
  const CameraInspection in = inspect_camera(frame.left, frame.right, simulator.cameras(), config.target, params);
  ASSERT_TRUE(in.report.found) << describe(in, params, simulator.cameras());
  EXPECT_LT(centre_error(in.report.centers, true_centers(simulator)), 0.01);
  int matched = 0, duplicates = 0;
  for (const BoardHypothesis& h : in.hypotheses) {
    if (h.stage == "duplicate") {
      ++duplicates;
      EXPECT_NE(h.reason.find("already found on plane #"), std::string::npos) << h.reason;
    } else {
      ++matched;
    }
  }
  EXPECT_EQ(matched, 1) << describe(in, params, simulator.cameras());
  EXPECT_GE(duplicates, 1) << describe(in, params, simulator.cameras());
}

// Paper setting 3, seed 5, frame 1: the board splits the wall 3 m behind it
// into pieces. The segmenter removed each piece on the grid of its refit
// plane, which no longer lined up with the patch it had found, so the same
// wall came back as every candidate and the board was never tried.
TEST(CameraDetection, AWallSplitByTheBoardDoesNotUseUpThePlaneCandidates) {
  auto config = sim::SimulationConfig::paper(3, "vlp16");
  config.frames = 2;
  config.seed = 5;
  const sim::DatasetSimulator simulator(config);
  const auto params = Calibrator::Params::preset("default");
  const auto frame = simulator.frame(1);
  const CameraInspection in = inspect_camera(frame.left, frame.right, simulator.cameras(), config.target, params);
  ASSERT_TRUE(in.report.found) << describe(in, params, simulator.cameras());
  EXPECT_LT(centre_error(in.report.centers, true_centers(simulator)), 0.01);
}

/// Frame 0 of random scene `seed` through the camera branch (default
/// preset): the board must be found, every centre within `tolerance` [m].
void expect_board_found_in_random_scene(std::uint64_t seed, double tolerance) {
  const auto params = Calibrator::Params::preset("default");
  const sim::RandomScene scene = sim::make_random_scene(seed, 1, 1.0, 1, sim::BoardDraw::Classic);
  const auto frame = scene.simulator->frame(0);
  const CameraInspection in = inspect_camera(frame.left, frame.right, scene.simulator->cameras(),
                                             scene.simulator->config().target, params);
  ASSERT_TRUE(in.report.found) << scene.summary << "\n" << describe(in, params, scene.simulator->cameras());
  EXPECT_LT(centre_error(in.report.centers, true_centers(*scene.simulator)), tolerance) << scene.summary;
}

// Boards before a brick wall metres behind them, seen by wide-baseline rigs
// (0.27 and 0.38 m): through each hole the left and right views see parts of
// the wall a whole number of brick periods apart, so the holes match at the
// board's disparity and looked covered; the board was rejected in every frame.
TEST(CameraDetection, HolesBeforeAFarBrickWallAreNotTakenAsCovered) {
  for (const std::uint64_t seed : {20, 44}) expect_board_found_in_random_scene(seed, 0.01);
}

// Gray boards before red brick walls in colour images: in gray the rims
// almost vanish (the bricks' luma is the board's) and the brick joints
// inside the holes are the strongest edges; the rim refinement then drifted
// (seed 7: 17.5 mm off) or failed and the board was rejected (seed 30). The
// refinement retries in colour, each rim sample taking its strongest channel.
TEST(CameraDetection, RimsThatDifferInHueMoreThanInBrightnessAreRefinedInColour) {
  for (const std::uint64_t seed : {7, 30}) expect_board_found_in_random_scene(seed, 0.012);
}

// The same kind of board (random scene 39, 1440 px, low-contrast board
// before bricks, colour): its gray edges gave sixteen circle candidates and
// no hole pattern, so the board was rejected before any refinement. Its
// edges are taken again in colour.
TEST(CameraDetection, HolesWhoseRimsShowOnlyInColourAreFoundWithColourEdges) {
  expect_board_found_in_random_scene(39, 0.01);
}

// Random scenes whose board's rim refinement diverged (rms 50 and 1840 px)
// while the circles' pose was kept: 0.41 m and 0.08 m off. A diverged
// refinement rejects the hypothesis, and no other hypothesis in these views
// is the board: nothing is found.
TEST(CameraDetection, AHypothesisWhoseRimRefinementDivergedIsNotKept) {
  const auto params = Calibrator::Params::preset("default");
  for (const auto& [seed, index] : {std::pair<std::uint64_t, int>{11, 0}, {29, 1}}) {
    const sim::RandomScene scene = sim::make_random_scene(seed, index + 1, 1.0, 1, sim::BoardDraw::Classic);
    const auto frame = scene.simulator->frame(index);
    const CameraInspection in = inspect_camera(frame.left, frame.right, scene.simulator->cameras(),
                                               scene.simulator->config().target, params);
    EXPECT_FALSE(in.report.found) << "seed " << seed << ": kept "
                                  << centre_error(in.report.centers, true_centers(*scene.simulator)) << " m off\n"
                                  << describe(in, params, scene.simulator->cameras());
  }
}

// When no hypothesis is verified, `l2s detect` shows the most board-like one
// as far as it went: with the rim refinement whose result rejected it, not
// "refinement off" and a board pose at the origin. The refiner here accepts
// no edge (as on an image without the board), so its refinement does not
// converge, and this board's holes show no stereo evidence to stand in for
// it: the board is rejected at its refinement.
TEST(CameraDetection, ARejectedHypothesisIsShownWithItsRefinement) {
  const sim::RandomScene scene = sim::make_random_scene(2010363691, 1, 1.0, 1, sim::BoardDraw::Classic);
  auto params = Calibrator::Params::preset("default");
  params.board_refiner.min_edge_strength = 1000.0;
  params.board_refiner.edge_noise_factor = 1000.0;
  const auto frame = scene.simulator->frame(0);
  const CameraInspection in = inspect_camera(frame.left, frame.right, scene.simulator->cameras(),
                                             scene.simulator->config().target, params);
  ASSERT_FALSE(in.report.found) << "the board is verified without rim edges";
  ASSERT_FALSE(in.hypotheses.empty());
  EXPECT_EQ(in.hypotheses.front().stage, "refine") << in.hypotheses.front().reason;
  ASSERT_TRUE(in.refined.has_value()) << describe(in, params, scene.simulator->cameras());
  ASSERT_TRUE(in.T_camera_board_initial.has_value());
  EXPECT_GT(in.T_camera_board_initial->translation().norm(), 1.0);
  EXPECT_EQ(describe(in, params, scene.simulator->cameras()).find("refine_camera_pose: false"), std::string::npos);
}

// A board of nearly the gray of the wall behind it, slightly blurred: its
// rims are gradients of 3-5 gray levels / px, below the 6 that an ordinary
// board's rims clear by far. The rim refinement (and with it the
// verification) lowers its threshold to the rims' own contrast, above the
// image noise; before, it confirmed 7 % (95 deg lens, Avia scene) and 0 %
// (Mid-360 scene, raw 1280x720) of the rims and the board was lost.
struct LowContrastCase {
  const char* name;
  std::uint64_t seed;
};

class CameraDetectionLowContrast : public ::testing::TestWithParam<LowContrastCase> {};

TEST_P(CameraDetectionLowContrast, FindsTheBoardByItsFaintRims) {
  const sim::RandomScene scene = sim::make_random_scene(GetParam().seed, 1, 1.0, 1, sim::BoardDraw::Classic);
  const auto params = Calibrator::Params::preset("default");
  const auto frame = scene.simulator->frame(0);
  const CameraInspection in = inspect_camera(frame.left, frame.right, scene.simulator->cameras(),
                                             scene.simulator->config().target, params);
  ASSERT_TRUE(in.report.found) << scene.summary << "\n" << describe(in, params, scene.simulator->cameras());
  ASSERT_TRUE(in.refined.has_value());
  EXPECT_TRUE(in.refined->converged) << in.refined->reason;
  EXPECT_LT(in.refined->edge_strength, params.board_refiner.min_edge_strength);
  // Centres in the physical left camera's frame (raw images are rectified inside).
  const auto& simulator = *scene.simulator;
  const Eigen::Isometry3d T_camera_board =
      simulator.config().rig.T_cambody_optical(0).inverse() * simulator.scene().T_cambody_board;
  const auto holes = simulator.config().target.hole_centers();
  for (int h = 0; h < 4; ++h)
    EXPECT_LT((in.report.centers[h] - T_camera_board * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0)).norm(), 0.01)
        << hole_name(static_cast<Hole>(h));
}

// Boards of nearly the gray of the wall behind them, where two holes' rims
// are steps of 3-5 gray levels spread over 5 px: ~1 gray level / px, below
// the image noise per sample. The rims elsewhere (a pillar behind the
// board) carried the rim refinement, but only 20 % of the rim samples found
// an edge and the verifier rejected the board in every frame (a 1920x1200
// camera, the board 2.3 m away before a plain wall; a 752x480 one before
// tiles). Summed along arcs of the rims the steps stand far above their
// noise, and not on the face around the holes. The pose rests on the rims
// with edges: in the first scene those of two holes, which leave the
// board's turn about them to the stereo depth (0.25 px of disparity is 14
// mm at 2.3 m on that rig; frame 0's worst centre is 21 mm off, mostly in
// depth, the 30 frames' calibration 3.5 mm).
TEST(CameraDetection, RimsFainterThanTheNoisePerSampleAreConfirmedAlongArcs) {
  for (const std::uint64_t seed : {1101176455, 1405632196}) expect_board_found_in_random_scene(seed, 0.03);
}

// A 640x480 camera with a 93 deg lens and a short baseline (fx B 25 px m),
// the board 1.8 m away before bricks: each hole is ~20 px across, SGM fills
// the holes with the board's depth, and the mortar lines seen through them
// make circle candidates stronger than the rims; no four candidates formed
// the pattern in any frame. The pattern's own votes find it.
TEST(CameraDetection, ASmallLowResolutionBoardBeforeBricksIsFoundByItsPattern) {
  const sim::RandomScene scene = sim::make_random_scene(1468088629, 2, 1.0, 1, sim::BoardDraw::Classic);
  const auto params = Calibrator::Params::preset("default");
  const auto frame = scene.simulator->frame(1);  // frame 0's rims are confirmed at 28 %, below the verifier's 30 %
  const CameraInspection in = inspect_camera(frame.left, frame.right, scene.simulator->cameras(),
                                             scene.simulator->config().target, params);
  ASSERT_TRUE(in.report.found) << scene.summary << "\n" << describe(in, params, scene.simulator->cameras());
  ASSERT_TRUE(in.circles.has_value());
  EXPECT_TRUE(in.circles->by_pattern_votes);
  // The right holes, not a neighbouring placement (0.4-0.5 m away); this rig
  // resolves depth to ~3 cm at 1.8 m (0.25 px of 14 px disparity).
  EXPECT_LT(centre_error(in.report.centers, true_centers(*scene.simulator)), 0.03);
}

// Boards before tiled or brick walls whose joints, seen through the holes,
// are stronger edges than the rims next to them: taking the strongest edge
// near each rim, the rim refinement followed the joints and did not
// converge, and the frames kept the stereo circles, pulled the same way in
// every frame of the scene (a matte board before tiles: 43.5 mm off in
// frame 0, not found in frame 1; a wood board before bricks: 13.8 mm). The
// refinement tries again taking each rim's first edge from the board's face.
TEST(CameraDetection, RimsBeforeWallJointsAreRefinedOnTheRimsNotTheJoints) {
  const auto params = Calibrator::Params::preset("default");
  for (const auto& [seed, index] : {std::pair<std::uint64_t, int>{1653306487, 0}, {1653306487, 1}, {1060328696, 1}}) {
    const sim::RandomScene scene = sim::make_random_scene(seed, index + 1, 1.0, 1, sim::BoardDraw::Classic);
    const auto frame = scene.simulator->frame(index);
    const CameraInspection in = inspect_camera(frame.left, frame.right, scene.simulator->cameras(),
                                               scene.simulator->config().target, params);
    ASSERT_TRUE(in.report.found) << scene.summary << "\n" << describe(in, params, scene.simulator->cameras());
    EXPECT_GT(in.report.rim_rms_px, 0.0) << scene.summary << ": " << in.report.note;  // refined
    EXPECT_LT(centre_error(in.report.centers, true_centers(*scene.simulator)), 0.004) << scene.summary;  // 0.2-2.1 mm
  }
}

// Random scenes where the camera branch kept a patch of the wall behind the
// board as the board, metres off (brick or tile walls, the board low in
// contrast or small in the image): the verifier passed them on the rims the
// circle fit found in the wall's joints. Either the board is found, or
// nothing: never a wall. Each case was kept 2-4.5 m off before. The last
// three were kept (2.1-3.4 m off: a box, a wall patch) on a rim refinement
// that did not converge, with no hole seen open to confirm them.
struct WallPatchCase {
  const char* name;
  std::uint64_t seed;
  int frame;
  bool board_found;  // the board itself is found in this view (else nothing is)
};

void PrintTo(const WallPatchCase& c, std::ostream* os) { *os << c.name; }

class CameraDetectionWallPatches : public ::testing::TestWithParam<WallPatchCase> {};

TEST_P(CameraDetectionWallPatches, NeverKeepsAPatchOfWallAsTheBoard) {
  const sim::RandomScene scene = sim::make_random_scene(GetParam().seed, std::max(3, GetParam().frame + 1), 1.0, 1,
                                                        sim::BoardDraw::Classic);
  const auto params = Calibrator::Params::preset("default");
  const auto frame = scene.simulator->frame(GetParam().frame);
  const CameraInspection in = inspect_camera(frame.left, frame.right, scene.simulator->cameras(),
                                             scene.simulator->config().target, params);
  // A wall patch lies metres off; where the board itself is found, it may be
  // a few cm off in these small low-contrast views (seed 29, frame 2: 8.7 cm,
  // stereo circles kept when the rim refinement ends at 1.3 px). Where it is
  // not, nothing else may be taken for it.
  ASSERT_EQ(in.report.found, GetParam().board_found) << in.report.reason << "\n" << scene.summary;
  if (GetParam().board_found) {
    EXPECT_LT(centre_error(in.report.centers, true_centers(*scene.simulator)), 0.3)
        << scene.summary << "\n" << describe(in, params, scene.simulator->cameras());
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, CameraDetectionWallPatches,
                         ::testing::Values(WallPatchCase{"LowContrastBoardBeforeNearBricks640x480", 1468088629, 3, true},
                                           WallPatchCase{"Seed29", 29, 2, true}, WallPatchCase{"Seed35", 35, 1, false},
                                           WallPatchCase{"Seed39", 39, 2, true}, WallPatchCase{"Seed48", 48, 0, true},
                                           WallPatchCase{"Seed57", 57, 0, false},
                                           WallPatchCase{"BoxBesideAFaintBoardUnconverged", 1730360865, 5, false},
                                           WallPatchCase{"WallPatchUnconverged825320075", 825320075, 5, false},
                                           WallPatchCase{"WallPatchUnconverged2106797728", 2106797728, 0, false}),
                         [](const auto& info) { return std::string(info.param.name); });

INSTANTIATE_TEST_SUITE_P(Scenes, CameraDetectionLowContrast,
                         ::testing::Values(LowContrastCase{"PlainBoardBeforeItsGrayWall95DegLens", 2010363691},
                                           LowContrastCase{"LowContrastBoardRawImagesMid360Scene", 1795425164}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace l2s
