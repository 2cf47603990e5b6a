// Rendering any stereo rig: the board appears where the rig's camera_info
// (left.yaml, right.yaml) says it must, projected with OpenCV's own
// functions: through K and D for raw images, through R and P for rectified
// ones; and the ground truth of a raw dataset is relative to the physical
// left camera.

#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/simulation.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include <cmath>
#include <ostream>
#include <string>

namespace l2s::sim {
namespace {

constexpr double kDeg = 3.141592653589793 / 180.0;

struct RigCase {
  std::string name;
  int width, height;
  double hfov_deg, baseline;
  DistortionModel model;  ///< None with `real` = false: the ideal rectified rig
  bool real;              ///< lenses and mount of a real pair (StereoRig::with_real_lenses)
};

void PrintTo(const RigCase& c, std::ostream* os) { *os << c.name; }

StereoRig make_rig(const RigCase& c) {
  StereoRig rig;
  rig.width = c.width;
  rig.height = c.height;
  rig.horizontal_fov = c.hfov_deg * kDeg;
  rig.baseline = c.baseline;
  return c.real ? rig.with_real_lenses(c.model) : rig;
}

cv::Mat to_cv(const Eigen::MatrixXd& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}

/// Pixels of points given in the left camera frame of the dataset, as a user
/// of left.yaml / right.yaml computes them: raw images through K and D with
/// OpenCV (the right camera placed by R and P alone), rectified images by P.
std::vector<Eigen::Vector2d> project_like_a_user(const StereoCamera& cams, int index,
                                                 const std::vector<Eigen::Vector3d>& p_camera) {
  std::vector<Eigen::Vector2d> pixels;
  const CameraInfo& info = index == 0 ? cams.left : cams.right;
  if (cams.images == ImageKind::Rectified) {
    for (const Eigen::Vector3d& p : p_camera) pixels.push_back(info.project(p));
    return pixels;
  }
  // Physical frame of this camera from the rectification: p_rect_left = R_l p,
  // the right rectified camera sits B along x, p_phys = R^T p_rect.
  std::vector<cv::Point3d> points;
  for (const Eigen::Vector3d& p : p_camera) {
    Eigen::Vector3d q = cams.left.rectification_matrix * p;
    if (index == 1) q.x() -= cams.baseline();
    q = info.rectification_matrix.transpose() * q;
    points.emplace_back(q.x(), q.y(), q.z());
  }
  std::vector<cv::Point2d> out;
  const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
  const cv::Mat D = cv::Mat(info.distortion_coefficients, true).reshape(1, 1);
  if (info.distortion_model == "equidistant")
    cv::fisheye::projectPoints(points, out, zero, zero, to_cv(info.camera_matrix), D);
  else
    cv::projectPoints(points, zero, zero, to_cv(info.camera_matrix), D, out);
  for (const cv::Point2d& p : out) pixels.emplace_back(p.x, p.y);
  return pixels;
}

/// Board-frame points that must be seen as board and points that must not:
/// rings a few pixels inside and outside each hole rim and the board outline.
struct Probes {
  std::vector<Eigen::Vector3d> board, not_board;
};

Probes rim_probes(const Target& t, double margin_m) {
  Probes probes;
  for (const Eigen::Vector2d& c : t.hole_centers())
    for (int k = 0; k < 32; ++k) {
      const Eigen::Vector2d dir(std::cos(k * kDeg * 11.25), std::sin(k * kDeg * 11.25));
      const Eigen::Vector2d on = c + (t.hole_radius + margin_m) * dir;
      const Eigen::Vector2d in = c + (t.hole_radius - margin_m) * dir;
      probes.board.emplace_back(on.x(), on.y(), 0.0);
      probes.not_board.emplace_back(in.x(), in.y(), 0.0);
    }
  const double w = 0.5 * t.board_width, h = 0.5 * t.board_height;
  for (int k = 0; k <= 20; ++k) {
    const double s = -0.9 + 1.8 * k / 20.0;
    for (double sign : {-1.0, 1.0}) {
      probes.board.emplace_back(s * w, sign * (h - margin_m), 0.0);
      probes.not_board.emplace_back(s * w, sign * (h + margin_m), 0.0);
      probes.board.emplace_back(sign * (w - margin_m), s * h, 0.0);
      probes.not_board.emplace_back(sign * (w + margin_m), s * h, 0.0);
    }
  }
  return probes;
}

void expect_board_where_projected(const StereoRig& rig, const BoardPose& pose) {
  const Scene scene = make_scene(Target{}, pose);
  StereoRenderer::Params params;
  params.edge_samples = 1;  // labels come from pixel centres anyway
  const CleanStereo clean = StereoRenderer(rig, params).render(RayCaster(scene));
  const StereoCamera cams = rig.cameras();

  // Probes 4 px off every edge at the board's distance (the hole's inner wall
  // shows as a crescent of up to 2 px at this yaw).
  const double margin = 4.0 * pose.x / cams.left.fx();
  const Probes probes = rim_probes(scene.target, margin);
  const Eigen::Isometry3d T_camera_board =
      (rig.T_cambody_optical(0) * rig.T_optical_camera()).inverse() * scene.T_cambody_board;
  for (int index = 0; index < 2; ++index) {
    const CleanImage& image = index == 0 ? clean.left : clean.right;
    for (bool expect_board : {true, false}) {
      std::vector<Eigen::Vector3d> p_camera;
      for (const Eigen::Vector3d& p : expect_board ? probes.board : probes.not_board)
        p_camera.push_back(T_camera_board * p);
      const std::vector<Eigen::Vector2d> pixels = project_like_a_user(cams, index, p_camera);
      int wrong = 0;
      for (const Eigen::Vector2d& px : pixels) {
        const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
        ASSERT_TRUE(u >= 0 && v >= 0 && u < image.width && v < image.height) << "probe off-image";
        if ((image.surface_at(u, v) == SurfaceId::Board) != expect_board) ++wrong;
      }
      EXPECT_EQ(wrong, 0) << (index == 0 ? "left" : "right") << " image, probes "
                          << (expect_board ? "on" : "off") << " the board";
    }
  }
}

class RigRenderTest : public ::testing::TestWithParam<RigCase> {};

TEST_P(RigRenderTest, BoardIsRenderedWhereTheCameraInfoProjectsIt) {
  const StereoRig rig = make_rig(GetParam());
  // Near the image centre, and towards a corner where lenses distort most.
  const double half_width = 3.2 * std::tan(0.5 * rig.horizontal_fov);
  for (const BoardPose& pose : {BoardPose{3.2, 0.15, -0.1, 0.3, 0.05, 0.05},
                                BoardPose{3.2, -0.5 * half_width, -0.6, -0.2, 0.0, 0.05}}) {
    SCOPED_TRACE("board at y = " + std::to_string(pose.y));
    expect_board_where_projected(rig, pose);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Rigs, RigRenderTest,
    ::testing::Values(
        RigCase{"Wide1920x1200_B030", 1920, 1200, 90.0, 0.30, DistortionModel::None, false},
        RigCase{"Vga_B007", 640, 480, 66.0, 0.07, DistortionModel::None, false},
        RigCase{"Issue1280x960_RawPlumbBob", 1280, 960, 66.0, 0.12, DistortionModel::PlumbBob, true},
        RigCase{"Wide1280x960_RawEquidistant", 1280, 960, 100.0, 0.25, DistortionModel::Equidistant, true},
        RigCase{"TiltedPairRectified", 1280, 960, 66.0, 0.12, DistortionModel::None, true}),
    [](const auto& info) { return info.param.name; });

class RawDatasetTest : public ::testing::TestWithParam<DistortionModel> {};

TEST_P(RawDatasetTest, GroundTruthIsRelativeToThePhysicalLeftCamera) {
  // Lidar board returns, moved into the camera frame by the true transform and
  // projected with left.yaml (OpenCV), land on board pixels of the raw image.
  SimulationConfig config = SimulationConfig::paper(3, "hdl64");
  config.frames = 1;
  config.rig.width = 1280;
  config.rig.height = 960;
  config.rig.horizontal_fov = 66.0 * kDeg;
  config.rig = config.rig.with_real_lenses(GetParam());
  const DatasetSimulator simulator(config);
  const StereoCamera cams = simulator.cameras();
  ASSERT_EQ(cams.images, GetParam() == DistortionModel::None ? ImageKind::Rectified : ImageKind::Raw);

  LidarSimulator::Params params;
  params.noise_factor = 0.0;
  std::vector<SurfaceId> surfaces;
  const LidarCloud cloud = LidarSimulator(LidarModel::hdl64(), params)
                               .sweep(RayCaster(simulator.scene()), config.setting.T_cambody_lidar(), 0, &surfaces);
  const Eigen::Isometry3d T_camera_lidar = simulator.T_lidar_camera().inverse();
  std::vector<Eigen::Vector3d> p_camera;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (surfaces[i] == SurfaceId::Board) p_camera.push_back(T_camera_lidar * cloud.points[i]);
  ASSERT_GT(p_camera.size(), 200u);
  const CleanImage& left = simulator.clean_images().left;
  int near = 0;
  for (const Eigen::Vector2d& px : project_like_a_user(cams, 0, p_camera)) {
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    bool any = false;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du)
        any = any || left.surface_at(std::clamp(u + du, 0, left.width - 1),
                                     std::clamp(v + dv, 0, left.height - 1)) == SurfaceId::Board;
    near += any;
  }
  EXPECT_EQ(near, static_cast<int>(p_camera.size()));
}

INSTANTIATE_TEST_SUITE_P(Lenses, RawDatasetTest,
                         ::testing::Values(DistortionModel::PlumbBob, DistortionModel::Equidistant,
                                           DistortionModel::None),
                         [](const auto& info) { return std::string(name_of(info.param)); });

}  // namespace
}  // namespace l2s::sim
