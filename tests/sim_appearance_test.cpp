// Scene looks: a brick wall repeats at the brick period, shadows darken
// exactly what a shadow ray says (also through and behind the holes), wood
// grain runs along the board, a low-contrast board is close to its
// background, the camera response (exposure, vignetting, blur, gamma,
// colour) does what its fields say, and every look's name parses back.
// The printed and painted board faces: sim_board_faces_test.cpp.

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <l2s/error.hpp>

#include "support/rendered_images.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace l2s::sim {
namespace {

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

TEST(Appearance, WoodGrainRunsAlongTheBoard) {
  const Scene scene = make_scene(Target{}, BoardPose{2.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  Appearance wood;
  wood.board = BoardTexture::WoodGrain;
  const FaceGradients g = face_gradients(render_left(scene, wood));
  ASSERT_GT(g.pixels, 20000);
  EXPECT_GT(g.across, 2.0 * g.along) << "streaks must run along the board's long side";
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
