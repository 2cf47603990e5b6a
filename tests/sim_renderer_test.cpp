// Rendered stereo images against scene geometry: lidar board points land on
// board pixels, stereo matching recovers the true disparity, and the noise
// has the paper's sigma.

#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

/// One auto-placed scene per setting with its clean rendering, shared by the tests.
struct Rendered {
  SensorSetting setting;
  Scene scene;
  CleanStereo clean;
};

const Rendered& rendered(int setting_index) {
  static std::map<int, Rendered> cache;
  auto it = cache.find(setting_index);
  if (it != cache.end()) return it->second;
  Rendered r;
  r.setting = paper_setting(setting_index);
  const PlacementResult placed = find_placement(
      Target{}, r.setting, {LidarModel::vlp16(), LidarModel::hdl32(), LidarModel::hdl64()});
  EXPECT_TRUE(placed.found);
  r.scene = make_scene(Target{}, placed.pose);
  r.clean = StereoRenderer(StereoRig{}).render(RayCaster(r.scene));
  return cache.emplace(setting_index, std::move(r)).first->second;
}

cv::Mat to_mat(const Image& image) {
  return cv::Mat(image.height, image.width, CV_8UC1, const_cast<std::uint8_t*>(image.pixels.data()));
}

class RendererSettingTest : public ::testing::TestWithParam<int> {};

TEST_P(RendererSettingTest, LidarBoardPointsProjectOntoBoardPixels) {
  const Rendered& r = rendered(GetParam());
  const RayCaster caster(r.scene);
  LidarSimulator::Params params;
  params.noise_factor = 0.0;
  std::vector<SurfaceId> surfaces;
  const LidarCloud cloud =
      LidarSimulator(LidarModel::hdl64(), params).sweep(caster, r.setting.T_cambody_lidar(), 0, &surfaces);
  const StereoCamera cams = StereoRig{}.cameras();
  // The TRUE transform maps lidar points into the left optical frame.
  const Eigen::Isometry3d T_camera_lidar = r.setting.T_lidar_camera().inverse();
  const CleanImage& left = r.clean.left;
  int board_points = 0, exact = 0, near = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (surfaces[i] != SurfaceId::Board) continue;
    const Eigen::Vector2d px = cams.left.project(T_camera_lidar * cloud.points[i]);
    ASSERT_TRUE(px.allFinite());
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    ASSERT_TRUE(u >= 0 && v >= 0 && u < left.width && v < left.height) << "board point off-image";
    ++board_points;
    if (left.surface_at(u, v) == SurfaceId::Board) ++exact;
    bool any = false;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du)
        any = any || left.surface_at(std::clamp(u + du, 0, left.width - 1),
                                     std::clamp(v + dv, 0, left.height - 1)) == SurfaceId::Board;
    if (any) ++near;
  }
  ASSERT_GT(board_points, 200);
  // Points on the rim may project to a pixel whose centre sees through the hole,
  // but never farther than one pixel away from the board.
  EXPECT_EQ(near, board_points);
  EXPECT_GT(exact, 0.97 * board_points);
}

TEST_P(RendererSettingTest, StereoMatchingRecoversTheTrueDisparity) {
  const Rendered& r = rendered(GetParam());
  const StereoRig rig;
  const StereoImages images = StereoRenderer(rig).add_noise(r.clean, 1.0, 7, 0);
  auto sgbm = cv::StereoSGBM::create(0, 128, 5, 8 * 25, 32 * 25, 1, 0, 10, 100, 2,
                                     cv::StereoSGBM::MODE_SGBM);
  cv::Mat disparity16;
  sgbm->compute(to_mat(images.left), to_mat(images.right), disparity16);

  // Board pixels well inside the board (eroded mask), with the true depth of
  // their centre ray.
  cv::Mat board(rig.height, rig.width, CV_8UC1);
  for (int v = 0; v < rig.height; ++v)
    for (int u = 0; u < rig.width; ++u)
      board.at<std::uint8_t>(v, u) = r.clean.left.surface_at(u, v) == SurfaceId::Board ? 255 : 0;
  cv::erode(board, board, cv::Mat::ones(15, 15, CV_8UC1));
  const RayCaster caster(r.scene);
  const Eigen::Isometry3d T = rig.T_cambody_optical(0);
  std::vector<double> errors;
  for (int v = 0; v < rig.height; v += 3) {
    for (int u = 0; u < rig.width; u += 3) {
      if (!board.at<std::uint8_t>(v, u)) continue;
      const std::int16_t d16 = disparity16.at<std::int16_t>(v, u);
      if (d16 <= 0) continue;
      const Eigen::Vector3d d_opt((u - rig.cx()) / rig.fx(), (v - rig.cy()) / rig.fx(), 1.0);
      const Eigen::Vector3d d = T.linear() * d_opt.normalized();
      const Hit hit = caster.cast(T.translation(), d);
      const double z = hit.t * d_opt.normalized().z();
      errors.push_back(std::abs(d16 / 16.0 - rig.fx() * rig.baseline / z));
    }
  }
  ASSERT_GT(errors.size(), 2000u);
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  RecordProperty("median_abs_error_px", std::to_string(errors[errors.size() / 2]));
  EXPECT_LT(errors[errors.size() / 2], 0.5);
}

INSTANTIATE_TEST_SUITE_P(Settings, RendererSettingTest, ::testing::Values(1, 8, 9),
                         [](const auto& info) { return "setting" + std::to_string(info.param); });

TEST(StereoRenderer, BoardIsBrightWithStrongRimsAndModerateTexture) {
  const Rendered& r = rendered(1);
  const CleanImage& left = r.clean.left;
  double board = 0, wall = 0;
  int nb = 0, nw = 0;
  for (int v = 0; v < left.height; ++v)
    for (int u = 0; u < left.width; ++u) {
      if (left.surface_at(u, v) == SurfaceId::Board) board += left.at(u, v), ++nb;
      if (left.surface_at(u, v) == SurfaceId::Wall) wall += left.at(u, v), ++nw;
    }
  ASSERT_GT(nb, 10000);
  EXPECT_GT(board / nb - wall / nw, 0.25);

  // Sobel magnitude: weak inside the board, strong on its border and rims.
  const Image image = StereoRenderer(StereoRig{}).add_noise(left, 1.0, 3, 0, 0);
  cv::Mat gx, gy, mag;
  cv::Sobel(to_mat(image), gx, CV_32F, 1, 0);
  cv::Sobel(to_mat(image), gy, CV_32F, 0, 1);
  cv::magnitude(gx, gy, mag);
  int inside = 0, inside_strong = 0, rim = 0, rim_strong = 0;
  for (int v = 2; v < left.height - 2; ++v)
    for (int u = 2; u < left.width - 2; ++u) {
      bool uniform = true, board_edge = false;
      for (int dv = -2; dv <= 2; ++dv)
        for (int du = -2; du <= 2; ++du) {
          const SurfaceId s = left.surface_at(u + du, v + dv);
          uniform = uniform && s == SurfaceId::Board;
          board_edge = board_edge || (s != SurfaceId::Board && left.surface_at(u, v) == SurfaceId::Board &&
                                      std::abs(du) + std::abs(dv) == 1);
        }
      const bool strong = mag.at<float>(v, u) > 128.0f;
      if (uniform) ++inside, inside_strong += strong;
      if (board_edge) ++rim, rim_strong += strong;
    }
  EXPECT_LT(inside_strong, 0.01 * inside);
  EXPECT_GT(rim_strong, 0.9 * rim);
}

TEST(StereoRenderer, NoiseHasThePapersSigmaAndIgnoresThreads) {
  const Rendered& r = rendered(1);
  StereoRenderer::Params one, three;
  one.threads = 1;
  three.threads = 3;
  const Image a = StereoRenderer(StereoRig{}, one).add_noise(r.clean.left, 2.0, 11, 5, 0);
  const Image b = StereoRenderer(StereoRig{}, three).add_noise(r.clean.left, 2.0, 11, 5, 0);
  EXPECT_EQ(a.pixels, b.pixels);
  const Image c = StereoRenderer(StereoRig{}, one).add_noise(r.clean.left, 2.0, 11, 6, 0);
  EXPECT_NE(a.pixels, c.pixels);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int v = 0; v < a.height; ++v)
    for (int u = 0; u < a.width; ++u) {
      const double clean = r.clean.left.at(u, v) * 255.0;
      if (clean < 30 || clean > 225) continue;  // no clipping
      const double e = a.at(u, v) - clean;
      sum += e, sum2 += e * e, ++n;
    }
  // sigma = K * 0.007 on 0..1, plus the 1/sqrt(12) quantisation step.
  const double expected = std::sqrt(std::pow(2.0 * 0.007 * 255.0, 2) + 1.0 / 12.0);
  EXPECT_NEAR(sum / n, 0.0, 0.05);
  EXPECT_NEAR(std::sqrt(sum2 / n), expected, 0.05 * expected);
}

/// FNV-1a over raw bytes: a checksum that is the same on every run.
std::uint64_t fnv1a(const void* data, std::size_t size) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ULL;
  return h;
}

TEST(StereoRenderer, DefaultsRenderTheSameBytesAsBeforeAnyRigOrLook) {
  // Checksums taken at 7cbd45a, before rigs, raw images and looks existed:
  // the paper rig with the default appearance must not change by one bit.
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.1, -0.1, 0.3, 0.05, 0.05});
  const StereoRenderer renderer{StereoRig{}};
  const CleanStereo clean = renderer.render(RayCaster(scene));
  EXPECT_EQ(fnv1a(clean.left.intensity.data(), clean.left.intensity.size() * sizeof(float)),
            0x4f7293df59bf3f1aULL);
  EXPECT_EQ(fnv1a(clean.right.intensity.data(), clean.right.intensity.size() * sizeof(float)),
            0xaa79efd1da6c7ac4ULL);
  const StereoImages images = renderer.add_noise(clean, 1.0, 7, 3);
  EXPECT_EQ(fnv1a(images.left.pixels.data(), images.left.pixels.size()), 0x4c0c5ab8a06fb4d4ULL);
  EXPECT_EQ(fnv1a(images.right.pixels.data(), images.right.pixels.size()), 0x4769cfdd5370e1d1ULL);
}

TEST(StereoRenderer, RenderingDoesNotDependOnThreads) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.1, 0.0, 0.3, 0.0, 0.05});
  StereoRig rig;
  rig.width = 320;
  rig.height = 240;
  StereoRenderer::Params one, two;
  one.threads = 1;
  two.threads = 2;
  const CleanImage a = StereoRenderer(rig, one).render_camera(RayCaster(scene), 1);
  const CleanImage b = StereoRenderer(rig, two).render_camera(RayCaster(scene), 1);
  EXPECT_EQ(a.intensity, b.intensity);
  EXPECT_EQ(a.surface, b.surface);
}

}  // namespace
}  // namespace l2s::sim
