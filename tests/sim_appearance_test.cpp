// Scene looks: a brick wall repeats at the brick period, shadows darken
// exactly what a shadow ray says (also through and behind the holes), wood
// grain runs along the board, a speckle print gives the face edges in every
// direction that fade to gray where the dots are finer than a pixel, a noise
// print is coarser, chipboard shows warm flakes at every angle, a black board
// is darker than its wall and a white one matches a white wall, a logo and a
// sticker sit beside and across one hole's rim, a glossy board mirrors the
// sun where geometry says, a
// low-contrast board is close to its background, and the camera response
// (exposure, vignetting, blur, gamma, colour) does what its fields say.

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <vector>

namespace l2s::sim {
namespace {

StereoRig small_rig() {
  StereoRig rig;
  rig.width = 640;
  rig.height = 480;
  return rig;
}

CleanImage render_left(const Scene& scene, const Appearance& look, const StereoRig& rig = small_rig()) {
  StereoRenderer::Params params;
  params.appearance = look;
  return StereoRenderer(rig, params).render_camera(RayCaster(scene), 0);
}

/// Mean over rows of the normalised autocorrelation of the longest run of
/// wall pixels in each row, for lags 0..max_lag.
std::vector<double> wall_row_autocorrelation(const CleanImage& image, int max_lag) {
  std::vector<double> sum(static_cast<std::size_t>(max_lag + 1), 0.0);
  int rows = 0;
  for (int v = 0; v < image.height; ++v) {
    int best_begin = 0, best_len = 0;
    for (int u = 0; u < image.width;) {
      if (image.surface_at(u, v) != SurfaceId::Wall) {
        ++u;
        continue;
      }
      int end = u;
      while (end < image.width && image.surface_at(end, v) == SurfaceId::Wall) ++end;
      if (end - u > best_len) best_begin = u, best_len = end - u;
      u = end;
    }
    if (best_len < 4 * max_lag) continue;
    std::vector<double> x(static_cast<std::size_t>(best_len));
    double mean = 0.0;
    for (int i = 0; i < best_len; ++i) mean += x[i] = image.at(best_begin + i, v);
    mean /= best_len;
    for (double& value : x) value -= mean;
    double zero = 0.0;
    for (double value : x) zero += value * value;
    if (zero <= 0.0) continue;
    for (int lag = 0; lag <= max_lag; ++lag) {
      double c = 0.0;
      for (int i = 0; i + lag < best_len; ++i) c += x[i] * x[i + lag];
      sum[static_cast<std::size_t>(lag)] += c / zero;
    }
    ++rows;
  }
  EXPECT_GT(rows, 50) << "too few wall rows";
  for (double& value : sum) value /= std::max(rows, 1);
  return sum;
}

TEST(Appearance, BrickWallRepeatsAtTheBrickPeriod) {
  // The board off to one side; the wall faces the cameras 5 m away.
  SceneLayout layout;
  layout.wall_gap = 2.0;
  layout.default_clutter = false;
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 1.3, 0.3, 0.2, 0.0, 0.0}, layout);
  Appearance bricks;
  bricks.background = Background::Bricks;
  const StereoRig rig = small_rig();
  const double depth = 3.0 + layout.wall_gap;
  const double period_px = rig.fx() * (bricks.brick_length + bricks.joint_width) / depth;
  const int max_lag = static_cast<int>(2.0 * period_px);

  const std::vector<double> ac = wall_row_autocorrelation(render_left(scene, bricks), max_lag);
  int peak = static_cast<int>(0.6 * period_px);
  for (int lag = peak; lag <= static_cast<int>(1.5 * period_px); ++lag)
    if (ac[static_cast<std::size_t>(lag)] > ac[static_cast<std::size_t>(peak)]) peak = lag;
  EXPECT_NEAR(peak, period_px, 1.0);
  EXPECT_GT(ac[static_cast<std::size_t>(peak)], 0.3);
  EXPECT_GT(ac[static_cast<std::size_t>(peak)] - ac[static_cast<std::size_t>(std::lround(0.5 * period_px))], 0.3);

  // The paper suite's wall has no such period: no peak above the half-period trough.
  const std::vector<double> textured = wall_row_autocorrelation(render_left(scene, Appearance{}), max_lag);
  EXPECT_LT(textured[static_cast<std::size_t>(std::lround(period_px))] -
                textured[static_cast<std::size_t>(std::lround(0.5 * period_px))],
            0.05);
}

TEST(Appearance, TilesRepeatAtTheTileSize) {
  SceneLayout layout;
  layout.wall_gap = 1.5;
  layout.default_clutter = false;
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 1.3, 0.3, 0.2, 0.0, 0.0}, layout);
  Appearance tiles;
  tiles.background = Background::Tiles;
  tiles.brick_length = 0.2;
  tiles.joint_width = 0.005;
  const double period_px = small_rig().fx() * 0.205 / 4.5;
  const std::vector<double> ac =
      wall_row_autocorrelation(render_left(scene, tiles), static_cast<int>(2.0 * period_px));
  EXPECT_GT(ac[static_cast<std::size_t>(std::lround(period_px))], 0.3);
}

/// Pixels whose centre ray hits the wall or ground, split by whether a ray
/// from that point towards the sun is blocked, keeping only pixels whose
/// 3x3 neighbourhood shares surface and state (not supersampled).
struct ShadowSplit {
  std::vector<std::size_t> shadowed, lit, shadowed_through_hole, lit_through_hole_in_board_shadow;
};

ShadowSplit split_by_shadow(const Scene& scene, const StereoRig& rig, const Appearance& look) {
  const RayCaster caster(scene);
  const Eigen::Isometry3d T = rig.T_cambody_optical(0);
  const int W = rig.width, H = rig.height;
  std::vector<int> state(static_cast<std::size_t>(W) * H, -1);  // -1 other, 0 lit, 1 shadowed
  std::vector<bool> through_hole(state.size(), false), light_through_hole(state.size(), false);
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const Eigen::Vector3d d =
          (T.linear() * Eigen::Vector3d((u - rig.cx()) / rig.fx(), (v - rig.cy()) / rig.fx(), 1.0)).normalized();
      const Hit hit = caster.cast(T.translation(), d);
      if (hit.surface != SurfaceId::Wall && hit.surface != SurfaceId::Ground) continue;
      if (hit.normal.dot(look.to_light) <= 0.0) continue;
      const Eigen::Vector3d p = T.translation() + hit.t * d + 1e-5 * hit.normal;
      const std::size_t i = static_cast<std::size_t>(v) * W + u;
      state[i] = caster.cast(p, look.to_light).hit() ? 1 : 0;
      through_hole[i] = caster.hole_on_front_plane(T.translation(), d) >= 0;
      light_through_hole[i] = state[i] == 0 && caster.hole_on_front_plane(p, look.to_light) >= 0;
    }
  ShadowSplit split;
  for (int v = 1; v + 1 < H; ++v)
    for (int u = 1; u + 1 < W; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * W + u;
      if (state[i] < 0) continue;
      bool uniform = true;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du) uniform = uniform && state[i + dv * W + du] == state[i];
      if (!uniform) continue;
      (state[i] ? split.shadowed : split.lit).push_back(i);
      if (state[i] == 1 && through_hole[i]) split.shadowed_through_hole.push_back(i);
      if (light_through_hole[i]) split.lit_through_hole_in_board_shadow.push_back(i);
    }
  return split;
}

TEST(Appearance, HardShadowsDarkenExactlyWhatTheSunCannotSee) {
  // A wall 1 m behind the board: the board's shadow, with four bright discs
  // of light through its holes, falls on the wall below and to the right,
  // and part of that shadow is seen through the holes.
  SceneLayout layout;
  layout.wall_gap = 1.0;
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.2, 0.1, 0.15, 0.0, 0.03}, layout);
  Appearance lit_look;
  lit_look.ambient = 0.3;
  Appearance shadow_look = lit_look;
  shadow_look.shadows = true;
  const StereoRig rig = small_rig();
  const CleanImage without = render_left(scene, lit_look, rig);
  const CleanImage with = render_left(scene, shadow_look, rig);
  const ShadowSplit split = split_by_shadow(scene, rig, shadow_look);
  ASSERT_GT(split.shadowed.size(), 2000u);
  ASSERT_GT(split.shadowed_through_hole.size(), 50u) << "no shadow seen through a hole";
  ASSERT_GT(split.lit_through_hole_in_board_shadow.size(), 50u) << "no light through a hole";

  for (std::size_t i : split.lit) EXPECT_EQ(with.intensity[i], without.intensity[i]);
  for (std::size_t i : split.lit_through_hole_in_board_shadow) EXPECT_EQ(with.intensity[i], without.intensity[i]);
  // In shadow only the ambient share stays: ratio = a / (a + (1 - a) * lambert) < 1.
  const Eigen::Vector3d wall_normal = -Eigen::Vector3d::UnitX();
  const double lambert = wall_normal.dot(shadow_look.to_light);
  const double ground_lambert = Eigen::Vector3d::UnitZ().dot(shadow_look.to_light);
  int darker = 0;
  for (std::size_t i : split.shadowed) {
    const double ratio = with.intensity[i] / without.intensity[i];
    const double expected_wall = 0.3 / (0.3 + 0.7 * lambert);
    const double expected_ground = 0.3 / (0.3 + 0.7 * ground_lambert);
    const bool matches = std::abs(ratio - expected_wall) < 1e-5 || std::abs(ratio - expected_ground) < 1e-5;
    darker += matches;
  }
  EXPECT_EQ(darker, static_cast<int>(split.shadowed.size()));
}

/// Mean absolute differences between neighbouring pixels of the board's face,
/// along the image rows and across them, over pixels 2 px or more from the
/// face's edges and holes.
struct FaceGradients {
  double along = 0.0;
  double across = 0.0;
  int pixels = 0;
};

FaceGradients face_gradients(const CleanImage& image) {
  FaceGradients g;
  for (int v = 2; v + 2 < image.height; ++v)
    for (int u = 2; u + 2 < image.width; ++u) {
      bool inside = true;
      for (int d = -2; d <= 2; ++d)
        inside = inside && image.surface_at(u + d, v) == SurfaceId::Board &&
                 image.surface_at(u, v + d) == SurfaceId::Board;
      if (!inside) continue;
      g.along += std::abs(image.at(u + 1, v) - image.at(u, v));
      g.across += std::abs(image.at(u, v + 1) - image.at(u, v));
      ++g.pixels;
    }
  if (g.pixels > 0) g.along /= g.pixels, g.across /= g.pixels;
  return g;
}

TEST(Appearance, WoodGrainRunsAlongTheBoard) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  Appearance wood;
  wood.board = BoardTexture::WoodGrain;
  const FaceGradients g = face_gradients(render_left(scene, wood));
  ASSERT_GT(g.pixels, 20000);
  EXPECT_GT(g.across, 2.0 * g.along) << "streaks must run along the board's long side";
}

TEST(Appearance, SpecklePrintGivesTheFaceFarMoreEdgesThanTheMatteFace) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  Appearance speckle;
  speckle.board = BoardTexture::Speckle;
  const CleanImage printed = render_left(scene, speckle);
  const FaceGradients matte = face_gradients(render_left(scene, Appearance{}));
  const FaceGradients print = face_gradients(printed);
  ASSERT_GT(print.pixels, 20000);
  ASSERT_GT(matte.pixels, 20000);
  EXPECT_GT(print.along, 5.0 * matte.along);
  EXPECT_GT(print.across, 5.0 * matte.across);
  // Dots, not stripes: as many edges along the rows as across them.
  EXPECT_NEAR(print.along / print.across, 1.0, 0.2);

  // Dark dots on light paper: the face's darkest tenth far below its median.
  std::vector<float> face;
  for (int v = 0; v < printed.height; ++v)
    for (int u = 0; u < printed.width; ++u)
      if (printed.surface_at(u, v) == SurfaceId::Board) face.push_back(printed.at(u, v));
  std::sort(face.begin(), face.end());
  ASSERT_FALSE(face.empty());
  EXPECT_LT(face[face.size() / 10], 0.6 * face[face.size() / 2]);
}

TEST(Appearance, SpeckleFinerThanAPixelFadesToGrayInsteadOfAliasing) {
  Appearance speckle;
  speckle.board = BoardTexture::Speckle;
  const auto board_at = [](double distance) {
    return make_scene(Target{}, BoardPose{distance, 0.0, 0.0, 0.0, 0.0, 0.0});
  };
  const FaceGradients near = face_gradients(render_left(board_at(2.0), speckle));
  const FaceGradients far = face_gradients(render_left(board_at(8.0), speckle));
  ASSERT_GT(far.pixels, 500);
  // At 8 m a pixel spans about two dots' cells: their contrast averages out.
  EXPECT_LT(far.along, 0.5 * near.along);
}

double mean_of(const CleanImage& image, SurfaceId surface) {
  double sum = 0.0;
  int n = 0;
  for (int v = 0; v < image.height; ++v)
    for (int u = 0; u < image.width; ++u)
      if (image.surface_at(u, v) == surface) sum += image.at(u, v), ++n;
  return n ? sum / n : 0.0;
}

/// Gray values of the board's front-facing pixels.
std::vector<double> face_values(const CleanImage& image) {
  std::vector<double> values;
  for (int v = 0; v < image.height; ++v)
    for (int u = 0; u < image.width; ++u)
      if (image.surface_at(u, v) == SurfaceId::Board) values.push_back(image.at(u, v));
  return values;
}

double deviation_of(const std::vector<double>& values) {
  double mean = 0.0, square = 0.0;
  for (double x : values) mean += x;
  mean /= std::max<std::size_t>(values.size(), 1);
  for (double x : values) square += (x - mean) * (x - mean);
  return std::sqrt(square / std::max<std::size_t>(values.size(), 1));
}

TEST(Appearance, NoisePrintIsCoarserThanTheSpeckleAndAsStrong) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  Appearance speckle, noise;
  speckle.board = BoardTexture::Speckle;
  noise.board = BoardTexture::NoisePrint;
  const CleanImage fine = render_left(scene, speckle), coarse = render_left(scene, noise);
  const FaceGradients matte = face_gradients(render_left(scene, Appearance{}));
  const FaceGradients g = face_gradients(coarse);
  ASSERT_GT(g.pixels, 20000);
  EXPECT_GT(g.along, 3.0 * matte.along);
  // As much contrast as the speckle, in features several times larger: a
  // smaller step between neighbours for the same spread of gray.
  const double coarse_spread = deviation_of(face_values(coarse)), fine_spread = deviation_of(face_values(fine));
  EXPECT_GT(coarse_spread, 0.7 * fine_spread);
  EXPECT_LT(g.along / coarse_spread, 0.5 * face_gradients(fine).along / fine_spread);
}

TEST(Appearance, ChipboardShowsFlakesOfWood) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  Appearance chipboard;
  chipboard.board = BoardTexture::Chipboard;
  const FaceGradients matte = face_gradients(render_left(scene, Appearance{}));
  const FaceGradients g = face_gradients(render_left(scene, chipboard));
  ASSERT_GT(g.pixels, 20000);
  EXPECT_GT(g.along, 2.5 * matte.along);
  EXPECT_NEAR(g.along / g.across, 1.0, 0.2) << "flakes lie at every angle";
  // Wood: warmer than neutral in a colour image.
  chipboard.colour = true;
  const CleanImage colour = render_left(scene, chipboard);
  double blue = 0.0, red = 0.0;
  for (int v = 0; v < colour.height; ++v)
    for (int u = 0; u < colour.width; ++u)
      if (colour.surface_at(u, v) == SurfaceId::Board) blue += colour.at(u, v, 0), red += colour.at(u, v, 2);
  EXPECT_GT(red, 1.5 * blue);
}

TEST(Appearance, ABlackBoardIsDarkerThanItsWallAndAWhiteOneMatchesAWhiteWall) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.1, 0.0, 0.2, 0.0, 0.0});
  for (Background background : {Background::Plain, Background::White, Background::Tiles}) {
    Appearance look;
    look.background = background;
    look.board = BoardTexture::Black;
    const CleanImage image = render_left(scene, look);
    EXPECT_LT(mean_of(image, SurfaceId::Board), 0.3 * mean_of(image, SurfaceId::Wall)) << name_of(background);
  }
  Appearance white;
  white.board = BoardTexture::White;
  white.background = Background::White;
  const CleanImage image = render_left(scene, white);
  EXPECT_LT(std::abs(mean_of(image, SurfaceId::Board) - mean_of(image, SurfaceId::Wall)), 0.08);
  const FaceGradients matte = face_gradients(render_left(scene, Appearance{}));
  EXPECT_LT(face_gradients(image).along, 2.0 * matte.along) << "painted white, almost no texture";
}

TEST(Appearance, LowContrastBoardIsCloseToItsBackground) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.1, 0.0, 0.2, 0.0, 0.0});
  for (Background background : {Background::Textured, Background::Bricks, Background::Tiles, Background::Plain}) {
    Appearance look;
    look.background = background;
    look.board = BoardTexture::LowContrast;
    const CleanImage image = render_left(scene, look);
    EXPECT_LT(std::abs(mean_of(image, SurfaceId::Board) - mean_of(image, SurfaceId::Wall)), 0.1)
        << name_of(background);
  }
  const CleanImage suite = render_left(scene, Appearance{});
  EXPECT_GT(mean_of(suite, SurfaceId::Board) - mean_of(suite, SurfaceId::Wall), 0.25);
}

/// Pixels where two renders of the same scene differ by more than `threshold`.
std::vector<Eigen::Vector2d> changed_pixels(const CleanImage& a, const CleanImage& b, double threshold) {
  std::vector<Eigen::Vector2d> pixels;
  for (int v = 0; v < a.height; ++v)
    for (int u = 0; u < a.width; ++u)
      if (std::abs(a.at(u, v) - b.at(u, v)) > threshold) pixels.emplace_back(u, v);
  return pixels;
}

/// The image of the target's hole centres on a board squarely facing the
/// camera `distance` ahead (board x along -y_body, board y along +z_body).
std::array<Eigen::Vector2d, 4> projected_holes(const StereoRig& rig, double distance) {
  std::array<Eigen::Vector2d, 4> image;
  const auto holes = Target{}.hole_centers();
  for (std::size_t k = 0; k < 4; ++k)
    image[k] = rig.project(0, Eigen::Vector3d(distance, -holes[k].x(), holes[k].y()));
  return image;
}

TEST(Appearance, ALogoAndItsLabelLieBesideOneHole) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  Appearance logo;
  logo.board = BoardTexture::Logo;
  const auto changed = changed_pixels(render_left(scene, logo), render_left(scene, Appearance{}), 0.1);
  ASSERT_GT(changed.size(), 200u);
  const StereoRig rig = small_rig();
  const auto holes = projected_holes(rig, 2.0);
  // Every printed pixel within 0.27 m of the same hole's centre (the next
  // hole is 0.4 m away).
  const double reach = 0.27 * rig.fx() / 2.0;
  int beside[4] = {0, 0, 0, 0};
  for (const auto& pixel : changed)
    for (std::size_t k = 0; k < 4; ++k) beside[k] += (pixel - holes[k]).norm() < reach;
  EXPECT_EQ(*std::max_element(beside, beside + 4), static_cast<int>(changed.size()));
}

TEST(Appearance, AStickerCrossesOneRim) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  Appearance sticker;
  sticker.board = BoardTexture::Sticker;
  const CleanImage image = render_left(scene, sticker);
  const auto changed = changed_pixels(image, render_left(scene, Appearance{}), 0.1);
  ASSERT_GT(changed.size(), 100u);
  const StereoRig rig = small_rig();
  const auto holes = projected_holes(rig, 2.0);
  const double radius = Target{}.hole_radius * rig.fx() / 2.0;
  // Sticker pixels right at a rim: a neighbour sees through the hole.
  int at_rim = 0;
  for (const auto& pixel : changed) {
    const int u = static_cast<int>(pixel.x()), v = static_cast<int>(pixel.y());
    bool near_hole = false;
    for (const auto& hole : holes) near_hole = near_hole || std::abs((pixel - hole).norm() - radius) < 3.0;
    if (!near_hole || u < 1 || v < 1 || u + 1 >= image.width || v + 1 >= image.height) continue;
    bool through = false;
    for (const auto& [du, dv] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}})
      through = through || image.surface_at(u + du, v + dv) != SurfaceId::Board;
    at_rim += through;
  }
  EXPECT_GT(at_rim, 5) << "the sticker's edge must meet the rim";
}

TEST(Appearance, AGlossyBoardShowsTheSunWhereItsMirrorDirectionPointsAtIt) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  const StereoRig rig = small_rig();
  const Eigen::Vector3d normal(-1.0, 0.0, 0.0);
  // Two points of the face (clear of the holes), in the camera body frame.
  for (const Eigen::Vector3d& point : {Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d(2.0, 0.35, 0.1)}) {
    Appearance glossy;
    glossy.board = BoardTexture::Glossy;
    const Eigen::Vector3d view = point.normalized();
    glossy.to_light = (view - 2.0 * view.dot(normal) * normal).normalized();
    const CleanImage image = render_left(scene, glossy);
    Eigen::Vector2d brightest(-1.0, -1.0);
    float peak = 0.0f;
    int saturated = 0;
    for (int v = 0; v < image.height; ++v)
      for (int u = 0; u < image.width; ++u) {
        if (image.surface_at(u, v) != SurfaceId::Board) continue;
        saturated += image.at(u, v) >= 1.0f;
        if (image.at(u, v) > peak) peak = image.at(u, v), brightest = Eigen::Vector2d(u, v);
      }
    EXPECT_GT(saturated, 100) << "the highlight saturates";
    // The highlight's top is flat (it falls by 2 % within 1 deg of the mirror
    // direction) while the laminate's mottling is 1 %: 8 px (2 cm) of play.
    EXPECT_LT((brightest - rig.project(0, point)).norm(), 8.0);
  }
  // A sun whose mirror image falls off the board leaves no highlight on it.
  Appearance glossy;
  glossy.board = BoardTexture::Glossy;
  const CleanImage image = render_left(scene, glossy);
  int saturated = 0;
  for (int v = 0; v < image.height; ++v)
    for (int u = 0; u < image.width; ++u) saturated += image.surface_at(u, v) == SurfaceId::Board && image.at(u, v) >= 1.0f;
  EXPECT_EQ(saturated, 0);
}

TEST(Appearance, CameraResponseFollowsItsFields) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.1, 0.0, 0.2, 0.0, 0.0});
  const CleanImage base = render_left(scene, Appearance{});
  const StereoRig rig = small_rig();

  Appearance exposure;
  exposure.exposure = 1.5;
  const CleanImage brighter = render_left(scene, exposure);
  for (std::size_t i = 0; i < base.intensity.size(); i += 997)
    EXPECT_NEAR(brighter.intensity[i], 1.5 * base.intensity[i], 1e-5);

  Appearance gamma;
  gamma.gamma = 2.2;
  const CleanImage encoded = render_left(scene, gamma);
  for (std::size_t i = 0; i < base.intensity.size(); i += 997)
    EXPECT_NEAR(encoded.intensity[i], std::pow(base.intensity[i], 1.0 / 2.2), 1e-5);

  Appearance vignetting;
  vignetting.vignetting = 0.4;
  const CleanImage vignetted = render_left(scene, vignetting);
  EXPECT_NEAR(vignetted.at(0, 0) / base.at(0, 0), 1.0 - 0.4 * (rig.cx() * rig.cx() + rig.cy() * rig.cy()) /
                                                           ((rig.cx() + 0.5) * (rig.cx() + 0.5) + (rig.cy() + 0.5) * (rig.cy() + 0.5)),
              1e-5);
  const int cu = static_cast<int>(rig.cx()), cv = static_cast<int>(rig.cy());
  EXPECT_NEAR(vignetted.at(cu, cv) / base.at(cu, cv), 1.0, 1e-5);

  Appearance blur;
  blur.blur_sigma = 1.2;
  const CleanImage blurred = render_left(scene, blur);
  // Energy of the second difference along rows: mostly detail near the
  // pixel scale, which a sigma = 1.2 px Gaussian all but removes.
  const auto detail = [](const CleanImage& image) {
    double sum = 0.0;
    for (int v = 0; v < image.height; ++v)
      for (int u = 1; u + 1 < image.width; ++u) {
        const double d2 = image.at(u + 1, v) - 2.0 * image.at(u, v) + image.at(u - 1, v);
        sum += d2 * d2;
      }
    return sum;
  };
  EXPECT_LT(detail(blurred), 0.2 * detail(base));
}

TEST(Appearance, ColourImagesHaveTheGrayImageAsLuma) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.1, 0.0, 0.2, 0.0, 0.0});
  Appearance gray;
  gray.board = BoardTexture::WoodGrain;
  gray.background = Background::Bricks;
  Appearance colour = gray;
  colour.colour = true;
  const CleanImage g = render_left(scene, gray);
  const CleanImage c = render_left(scene, colour);
  ASSERT_EQ(c.channels, 3);
  double worst = 0.0;
  for (int v = 0; v < g.height; ++v)
    for (int u = 0; u < g.width; ++u) {
      const double luma = 0.114 * c.at(u, v, 0) + 0.587 * c.at(u, v, 1) + 0.299 * c.at(u, v, 2);
      worst = std::max(worst, std::abs(luma - g.at(u, v)));
    }
  EXPECT_LT(worst, 1e-5);
  // Bricks are red: R above B on the wall.
  double red = 0.0, blue = 0.0;
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u)
      if (c.surface_at(u, v) == SurfaceId::Wall) red += c.at(u, v, 2), blue += c.at(u, v, 0);
  EXPECT_GT(red, 1.5 * blue);

  // Colour noise: three independent draws per pixel with the paper's sigma.
  StereoRenderer::Params params;
  params.appearance = colour;
  const Image noisy = StereoRenderer(small_rig(), params).add_noise(c, 2.0, 3, 0, 0);
  ASSERT_EQ(noisy.channels, 3);
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int v = 0; v < c.height; ++v)
    for (int u = 0; u < c.width; ++u)
      for (int k = 0; k < 3; ++k) {
        const double clean = c.at(u, v, k) * 255.0;
        if (clean < 30 || clean > 225) continue;
        const double e = noisy.at(u, v, k) - clean;
        sum += e, sum2 += e * e, ++n;
      }
  const double expected = std::sqrt(std::pow(2.0 * 0.007 * 255.0, 2) + 1.0 / 12.0);
  EXPECT_NEAR(sum / n, 0.0, 0.05);
  EXPECT_NEAR(std::sqrt(sum2 / n), expected, 0.03 * expected);
}

TEST(Appearance, ValidationNamesTheBadField) {
  Appearance look;
  look.blur_sigma = 5.0;
  try {
    look.validate();
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "appearance.blur_sigma");
  }
  look = Appearance{};
  look.to_light = Eigen::Vector3d(1.0, 1.0, 0.0);
  EXPECT_THROW(look.validate(), ParamError);
  EXPECT_EQ(board_texture_from_name("wood", "x"), BoardTexture::WoodGrain);
  EXPECT_EQ(board_texture_from_name("speckle", "x"), BoardTexture::Speckle);
  for (const std::string& name : board_texture_names()) EXPECT_EQ(name_of(board_texture_from_name(name, "x")), name);
  for (const std::string& name : background_names()) EXPECT_EQ(name_of(background_from_name(name, "x")), name);
  EXPECT_EQ(board_texture_names().size(), 11u);
  EXPECT_THROW(board_texture_from_name("speckles", "appearance.board_texture"), ParamError);
  EXPECT_THROW(background_from_name("brick", "appearance.background"), ParamError);
  EXPECT_TRUE(Appearance{}.is_default());
}

}  // namespace
}  // namespace l2s::sim
