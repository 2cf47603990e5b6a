// The random camera side of a scene: reproducible, within the ranges of
// issue 8, raw with distortion in about half the draws, every look drawn,
// boards (faces, markers, sizes and hole layouts) from streams of their own
// that leave the rest of a scene as it was, and every draw a valid rig and appearance that renders.

#include <l2s/sim/camera_scene_draw.hpp>
#include <l2s/sim/random_scene.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>

namespace l2s::sim {
namespace {

constexpr double kDeg = 3.141592653589793 / 180.0;

TEST(CameraSceneDraw, SameSeedSameDraws) {
  std::mt19937_64 a(42), b(42), c(43);
  for (int i = 0; i < 20; ++i) {
    const CameraSceneDraw x = draw_camera_scene(a), y = draw_camera_scene(b);
    EXPECT_EQ(x.summary(), y.summary());
    EXPECT_EQ(x.rig.lenses[1].distortion.coefficients, y.rig.lenses[1].distortion.coefficients);
    EXPECT_EQ(x.rig.right_rotation, y.rig.right_rotation);
    EXPECT_EQ(x.appearance.to_light, y.appearance.to_light);
    EXPECT_EQ(x.appearance.blur_sigma, y.appearance.blur_sigma);
  }
  EXPECT_NE(draw_camera_scene(c).summary(), draw_camera_scene(a).summary());
}

TEST(CameraSceneDraw, DrawsWithinTheIssueRangesAndCoverEveryLook) {
  std::mt19937_64 rng(7);
  constexpr int kDraws = 400;
  int raw = 0, shadows = 0, colour = 0, open = 0;
  std::map<DistortionModel, int> models;
  std::map<BoardTexture, int> boards;
  std::map<Background, int> backgrounds;
  for (int i = 0; i < kDraws; ++i) {
    const CameraSceneDraw d = draw_camera_scene(rng);
    SCOPED_TRACE(d.summary());
    ASSERT_NO_THROW(d.rig.validate());
    ASSERT_NO_THROW(d.appearance.validate());
    EXPECT_TRUE(d.rig.width >= 640 && d.rig.width <= 1920 && d.rig.height >= 480 && d.rig.height <= 1200);
    EXPECT_TRUE(d.rig.horizontal_fov >= 40 * kDeg && d.rig.horizontal_fov <= 100 * kDeg);
    EXPECT_TRUE(d.rig.baseline >= 0.07 && d.rig.baseline <= 0.5);
    EXPECT_TRUE(d.wall_gap >= 0.55 && d.wall_gap <= 6.0);
    EXPECT_TRUE(d.appearance.blur_sigma >= 0.0 && d.appearance.blur_sigma <= 1.2);
    EXPECT_LT(d.appearance.to_light.x(), 0.0) << "the sun lights the board's face";
    if (d.rig.images() == ImageKind::Raw) {
      ++raw;
      ++models[d.rig.lenses[0].distortion.model];
      EXPECT_TRUE(d.rig.lenses[0].distortion.distorts());
      EXPECT_FALSE(d.rig.ideal());
    } else {
      EXPECT_TRUE(d.rig.ideal());
    }
    shadows += d.appearance.shadows;
    colour += d.appearance.colour;
    open += d.open_space;
    ++boards[d.appearance.board];
    ++backgrounds[d.appearance.background];
  }
  EXPECT_NEAR(raw, kDraws / 2, kDraws / 10);
  EXPECT_GT(models[DistortionModel::PlumbBob], kDraws / 10);
  EXPECT_GT(models[DistortionModel::Equidistant], kDraws / 20);
  EXPECT_NEAR(shadows, 0.7 * kDraws, kDraws / 10);
  EXPECT_NEAR(colour, kDraws / 2, kDraws / 10);
  EXPECT_GT(open, kDraws / 20);
  EXPECT_EQ(boards.size(), 3u);
  EXPECT_EQ(backgrounds.size(), 4u);
}

TEST(CameraSceneDraw, PrintedFacesComeFromTheirOwnStreamInAboutHalfTheScenes) {
  std::mt19937_64 rng(7), same(7);
  constexpr int kDraws = 800;
  int printed = 0, black_on_dark = 0, white = 0, white_on_white = 0;
  std::map<BoardTexture, int> boards;
  for (int i = 0; i < kDraws; ++i) {
    const CameraSceneDraw classic = draw_camera_scene(same);
    CameraSceneDraw d = draw_camera_scene(rng);
    std::mt19937_64 faces(1000 + i);
    draw_board_face(faces, &d.appearance);
    // Only the face (and the wall behind a black or white one) changes.
    EXPECT_EQ(d.rig.width, classic.rig.width);
    EXPECT_EQ(d.appearance.to_light, classic.appearance.to_light);
    EXPECT_EQ(d.appearance.colour, classic.appearance.colour);
    ASSERT_NO_THROW(d.appearance.validate());
    const BoardTexture face = d.appearance.board;
    const bool is_classic =
        face == BoardTexture::Matte || face == BoardTexture::WoodGrain || face == BoardTexture::LowContrast;
    if (is_classic) {
      EXPECT_EQ(face, classic.appearance.board);
      EXPECT_EQ(d.appearance.background, classic.appearance.background);
    }
    printed += !is_classic;
    ++boards[face];
    black_on_dark += face == BoardTexture::Black && d.appearance.background == Background::Textured;
    white += face == BoardTexture::White;
    white_on_white += face == BoardTexture::White && d.appearance.background == Background::White;
  }
  EXPECT_NEAR(printed, kDraws / 2, kDraws / 16);
  EXPECT_EQ(boards.size(), 11u) << "every face drawn";
  for (const auto& [face, count] : boards) EXPECT_GT(count, kDraws / 40) << name_of(face);
  EXPECT_EQ(black_on_dark, 0);
  EXPECT_NEAR(white_on_white, white / 2, white / 4 + 1);
}

TEST(CameraSceneDraw, MarkersOnAThirdOfTheBoardsOfManyDictionaries) {
  std::mt19937_64 rng(11);
  constexpr int kDraws = 600;
  int marked = 0;
  std::set<std::string> dictionaries;
  for (int i = 0; i < kDraws; ++i) {
    Target target;
    draw_board_markers(rng, &target);
    if (!target.markers) continue;
    ++marked;
    ASSERT_NO_THROW(target.validate()) << target.markers->dictionary;
    dictionaries.insert(target.markers->dictionary);
    const auto& ids = target.markers->ids;
    EXPECT_EQ(std::set<int>(ids.begin(), ids.end()).size(), 4u) << "distinct ids";
    EXPECT_TRUE(target.markers->size >= 0.15 && target.markers->size <= 0.20);
  }
  EXPECT_NEAR(marked, kDraws / 3, kDraws / 15);
  EXPECT_EQ(dictionaries.size(), 8u);
}

TEST(CameraSceneDraw, BoardsOfOtherSizesAndHoleLayoutsAlwaysValidWithMarkersThatFit) {
  std::mt19937_64 rng(5), marker_rng(6);
  constexpr int kDraws = 500;
  int other = 0, small_holes = 0, large_holes = 0, marked = 0, own_layout = 0;
  for (int i = 0; i < kDraws; ++i) {
    Target target;
    draw_board_geometry(rng, &target);
    draw_board_markers(marker_rng, &target);
    ASSERT_NO_THROW(target.validate());
    const Target standard;
    if (target.board_width == standard.board_width && target.hole_radius == standard.hole_radius) continue;
    ++other;
    EXPECT_TRUE(target.board_width >= 0.8 && target.board_width <= 1.6);
    EXPECT_TRUE(target.board_height >= 0.6 && target.board_height <= target.board_width);
    small_holes += target.hole_radius < 0.08;
    large_holes += target.hole_radius > 0.13;
    if (!target.markers) continue;
    ++marked;
    own_layout += target.markers->centres != MarkerLayout::corners_default().centres;
  }
  EXPECT_NEAR(other, 0.4 * kDraws, kDraws / 15);
  EXPECT_GT(small_holes, other / 10);
  EXPECT_GT(large_holes, other / 20);
  EXPECT_GT(marked, other / 5);
  EXPECT_GT(own_layout, 0) << "boards without room for the default layout state their own";
}

TEST(RandomScene, TheBoardsDrawLeavesTheRestOfTheSceneAsItWas) {
  int faces = 0, markers = 0;
  // Seed 1 draws markers, 8 a printed face; neither another rig or a roll
  // (those are drawn apart as well: sim_mounting_test).
  for (const std::uint64_t seed : {1, 8}) {
    const RandomScene all = make_random_scene(seed, 1, 1.0, 1, BoardDraw::All);
    const RandomScene classic = make_random_scene(seed, 1, 1.0, 1, BoardDraw::Classic);
    SCOPED_TRACE(all.summary);
    const SimulationConfig& a = all.simulator->config();
    const SimulationConfig& c = classic.simulator->config();
    EXPECT_FALSE(c.target.markers.has_value());
    EXPECT_EQ(a.rig.width, c.rig.width);
    EXPECT_EQ(a.appearance.to_light, c.appearance.to_light);
    EXPECT_EQ(a.lidar, c.lidar);
    // The board stands as far as the rig resolves its holes: the same when they are.
    if (a.target.hole_radius == c.target.hole_radius) {
      EXPECT_EQ(all.simulator->board_pose().x, classic.simulator->board_pose().x);
    }
    faces += a.appearance.board != c.appearance.board;
    markers += a.target.markers.has_value();
  }
  EXPECT_GT(faces, 0);
  EXPECT_GT(markers, 0);
}

// Beyond the classic draw, some solid-state lidars keep their returns as one
// cloud accumulated over seconds (cropped around the board or not), drawn
// from a stream of its own: the rest of the scene is as the classic draw's.
TEST(RandomScene, SomeSolidStateLidarsKeepOneAccumulatedCloud) {
  // 664592208 draws 4 s of the whole scene, 1795425164 1.6 s cropped, both Mid-360-like.
  int cropped = 0;
  for (const std::uint64_t seed : {664592208, 1795425164}) {
    const RandomScene all = make_random_scene(seed, 1, 1.0, 1, BoardDraw::All);
    const RandomScene classic = make_random_scene(seed, 1, 1.0, 1, BoardDraw::Classic);
    SCOPED_TRACE(all.summary);
    const SimulationConfig& a = all.simulator->config();
    EXPECT_FALSE(all.simulator->lidar_model().has_rings());
    EXPECT_GE(a.accumulated_seconds, 1.0);
    EXPECT_LE(a.accumulated_seconds, 5.0);
    EXPECT_NE(all.summary.find("accumulated"), std::string::npos);
    if (a.accumulated_crop > 0.0) {
      ++cropped;
      EXPECT_GE(a.accumulated_crop, 0.2);
      EXPECT_LT(a.accumulated_crop, 0.6);
    }
    EXPECT_EQ(classic.simulator->config().accumulated_seconds, 0.0);
    if (classic.redraws == all.redraws) {  // a board that stands elsewhere may redraw the scene
      EXPECT_EQ(classic.simulator->config().lidar, a.lidar);
    }
  }
  EXPECT_EQ(cropped, 1);
}

// The marked boards the stereo branch's marker pose is measured on: every
// board carries markers, on a level rig with the lidar upright.
TEST(RandomScene, MarkedScenesCarryMarkersOnALevelRigWithTheLidarUpright) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    const RandomScene marked = make_random_scene(seed, 1, 1.0, 1, BoardDraw::Marked);
    SCOPED_TRACE(marked.summary);
    const SimulationConfig& m = marked.simulator->config();
    ASSERT_TRUE(m.target.markers.has_value());
    EXPECT_NO_THROW(m.target.validate());
    EXPECT_EQ(m.rig.roll, 0.0);
    EXPECT_GT(std::cos(m.setting.roll), 0.0);
  }
}

TEST(CameraSceneDraw, ADrawRendersAndItsCamerasRectify) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 30; ++i) {
    const CameraSceneDraw d = draw_camera_scene(rng);
    const StereoCamera cams = d.rig.cameras();
    EXPECT_EQ(cams.images, d.rig.images());
    EXPECT_GT(cams.baseline(), 0.06);
  }
  // One raw draw rendered whole: the board shows up in both images.
  CameraSceneDraw d;
  do d = draw_camera_scene(rng);
  while (d.rig.images() != ImageKind::Raw || d.open_space);
  SceneLayout layout;
  layout.wall_gap = d.wall_gap;
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.1, -0.1, 0.2, 0.0, 0.03}, layout);
  StereoRenderer::Params params;
  params.appearance = d.appearance;
  const CleanStereo clean = StereoRenderer(d.rig, params).render(RayCaster(scene));
  for (const CleanImage* image : {&clean.left, &clean.right}) {
    int board = 0;
    for (SurfaceId s : image->surface) board += s == SurfaceId::Board;
    EXPECT_GT(board, 1000) << d.summary();
  }
}

}  // namespace
}  // namespace l2s::sim
