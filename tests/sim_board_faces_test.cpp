// The board faces users print or paint, measured on rendered images: a
// speckle print gives the face edges in every direction that fade to gray
// where the dots are finer than a pixel, a noise print is coarser, chipboard
// shows warm flakes at every angle, a black board is darker than its wall and
// a white one matches a white wall, a logo and a sticker sit beside and
// across one hole's rim, and a glossy board mirrors the sun where geometry
// says.

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include "support/rendered_images.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace l2s::sim {
namespace {

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
    for (int u = 0; u < image.width; ++u)
      saturated += image.surface_at(u, v) == SurfaceId::Board && image.at(u, v) >= 1.0f;
  EXPECT_EQ(saturated, 0);
}

}  // namespace
}  // namespace l2s::sim
