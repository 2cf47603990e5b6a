// The frame inspector (l2s detect): the same centres as Calibrator::add, every
// stage's result kept, a failing stage named with a reason, debug pictures,
// and the tool's exit codes.

#include <l2s/calibrator.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/viz/inspection_images.hpp>
#include <l2s/sim/simulation.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <random>
#include <string>

namespace l2s {
namespace {

namespace fs = std::filesystem;

// One simulated frame of Table I setting 1 (VLP-16), shared by the cases.
class FrameInspector : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto config = sim::SimulationConfig::paper(1, "vlp16");
    config.frames = 1;
    simulator_ = std::make_unique<sim::DatasetSimulator>(config);
    frame_ = std::make_unique<sim::SimulatedFrame>(simulator_->frame(0));
  }
  static void TearDownTestSuite() {
    frame_.reset();
    simulator_.reset();
  }
  static const Target& target() { return simulator_->config().target; }

  static std::unique_ptr<sim::DatasetSimulator> simulator_;
  static std::unique_ptr<sim::SimulatedFrame> frame_;
};

std::unique_ptr<sim::DatasetSimulator> FrameInspector::simulator_;
std::unique_ptr<sim::SimulatedFrame> FrameInspector::frame_;

TEST_F(FrameInspector, FindsTheBoardOnBothSensorsWithTheCalibratorsCentres) {
  const auto params = Calibrator::Params::preset("default");
  const LidarInspection lidar = inspect_lidar(frame_->lidar, target(), params);
  const CameraInspection camera =
      inspect_camera(frame_->left, frame_->right, simulator_->cameras(), target(), params);
  ASSERT_TRUE(lidar.report.found) << lidar.report.failed_stage << ": " << lidar.report.reason;
  ASSERT_TRUE(camera.report.found) << camera.report.failed_stage << ": " << camera.report.reason;

  // Every stage ran and kept its result.
  ASSERT_TRUE(lidar.pass_through && lidar.plane && lidar.discontinuities && lidar.circles);
  EXPECT_TRUE(lidar.plane->found);
  ASSERT_GE(lidar.candidate, 0);
  EXPECT_EQ(lidar.plane->candidates[lidar.candidate].inliers.size(), lidar.report.plane_inliers);
  EXPECT_EQ(lidar.discontinuities->edges.size(), lidar.report.edge_points);
  EXPECT_EQ(lidar.cloud.size(), lidar.report.input_points);
  // The default preset locates the board at low resolution, then matches its region.
  ASSERT_TRUE(camera.located && camera.stereo && camera.plane && camera.edges && camera.circles);
  EXPECT_FALSE(camera.located->stereo.disparity.empty());
  EXPECT_FALSE(camera.stereo->disparity.empty());
  EXPECT_LT(camera.stereo->disparity.values.size(), camera.located->stereo.disparity.values.size() * 8);
  EXPECT_EQ(camera.located->cloud.size(), camera.report.input_points);
  EXPECT_EQ(camera.board.size(), camera.report.plane_inliers);
  EXPECT_TRUE(camera.T_camera_board_initial.has_value());
  EXPECT_TRUE(camera.refined.has_value());  // the default preset refines the rims
  for (int h = 0; h < 4; ++h) {
    EXPECT_GE(lidar.circles->matched[h], 0);
    EXPECT_GE(camera.circles->matched[h], 0);
  }

  // The centres are exactly what the calibrator takes from this frame.
  Calibrator calibrator(simulator_->cameras(), target(), params);
  const FrameReport report = calibrator.add(frame_->lidar, frame_->left, frame_->right, "0");
  ASSERT_TRUE(report.used());
  for (int h = 0; h < 4; ++h) {
    EXPECT_EQ(lidar.report.centers[h], report.lidar.centers[h]) << "hole " << h;
    EXPECT_EQ(camera.report.centers[h], report.camera.centers[h]) << "hole " << h;
  }
  EXPECT_EQ(lidar.report.plane_inliers, report.lidar.plane_inliers);
  EXPECT_EQ(camera.report.edge_points, report.camera.edge_points);

  // And they are the same holes: the true extrinsics map one set onto the other.
  const Eigen::Isometry3d T_lidar_camera = simulator_->T_lidar_camera();
  for (int h = 0; h < 4; ++h)
    EXPECT_LT((T_lidar_camera * camera.report.centers[h] - lidar.report.centers[h]).norm(), 0.03)
        << "hole " << h;

  const std::string lidar_text = describe(lidar, params);
  const std::string camera_text = describe(camera, params, simulator_->cameras());
  EXPECT_NE(lidar_text.find("lidar   FOUND"), std::string::npos) << lidar_text;
  EXPECT_NE(lidar_text.find("min_discontinuity 0.15 m"), std::string::npos) << lidar_text;
  EXPECT_NE(lidar_text.find("CHOSEN"), std::string::npos) << lidar_text;
  EXPECT_NE(lidar_text.find("TL  ("), std::string::npos) << lidar_text;
  EXPECT_NE(camera_text.find("camera  FOUND"), std::string::npos) << camera_text;
  EXPECT_NE(camera_text.find("sobel_threshold 128"), std::string::npos) << camera_text;

  const Image lidar_picture = render_lidar_inspection(lidar, target());
  EXPECT_EQ(lidar_picture.channels, 3);
  EXPECT_GT(lidar_picture.width, 800);
  const Image camera_picture =
      render_camera_inspection(frame_->left, camera, simulator_->cameras(), target());
  EXPECT_EQ(camera_picture.channels, 3);
  EXPECT_EQ(camera_picture.width, frame_->left.width);
  EXPECT_GT(camera_picture.height, frame_->left.height);  // banner and legend
  EXPECT_FALSE(render_disparity(camera).empty());
}

TEST_F(FrameInspector, SweepWithoutTheBoardNamesTheFailingStage) {
  const auto params = Calibrator::Params::preset("default");
  const LidarInspection found = inspect_lidar(frame_->lidar, target(), params);
  ASSERT_TRUE(found.report.found);
  Eigen::Vector3d board_centre = Eigen::Vector3d::Zero();
  for (const auto& c : found.report.centers) board_centre += c / 4.0;

  // Delete the board's returns: near its plane and within a board-sized ball.
  const Plane& board = found.plane->candidates[found.candidate].plane;
  LidarCloud sweep;
  for (std::size_t i = 0; i < frame_->lidar.size(); ++i) {
    const Eigen::Vector3d& p = frame_->lidar.points[i];
    if ((p - board_centre).norm() < 1.0 && std::abs(board.signedDistance(p)) < 0.1) continue;
    sweep.points.push_back(frame_->lidar.points[i]);
    sweep.ring.push_back(frame_->lidar.ring[i]);
  }
  const LidarInspection lost = inspect_lidar(sweep, target(), params);
  EXPECT_FALSE(lost.report.found);
  EXPECT_FALSE(lost.report.failed_stage.empty());
  EXPECT_FALSE(lost.report.reason.empty());
  EXPECT_NE(describe(lost, params).find("lidar   FAILED at " + lost.report.failed_stage),
            std::string::npos);
  // Nothing else in this scene is board-sized: the plane stage stops the
  // branch, says why for each candidate, and the later stages do not run.
  ASSERT_TRUE(lost.plane.has_value());
  EXPECT_FALSE(lost.plane->found);
  EXPECT_EQ(lost.report.failed_stage, "plane");
  EXPECT_NE(lost.report.reason.find("no board-sized plane"), std::string::npos) << lost.report.reason;
  EXPECT_FALSE(lost.discontinuities.has_value());
  EXPECT_FALSE(lost.circles.has_value());
  EXPECT_GT(render_lidar_inspection(lost, target()).width, 0);
}

TEST_F(FrameInspector, BlankSceneFailsInTheCameraBranchWithAReason) {
  // A textured wall filling the view at one disparity: stereo works, but no board.
  const auto& cameras = simulator_->cameras();
  const int width = cameras.left.width, height = cameras.left.height, disparity = 48;
  Image left(width, height), right(width, height);
  std::mt19937 random(3);
  std::uniform_int_distribution<int> grey(40, 215);
  std::vector<std::uint8_t> blocks(static_cast<std::size_t>((width + disparity) / 4 + 1) *
                                   (height / 4 + 1));
  for (auto& b : blocks) b = static_cast<std::uint8_t>(grey(random));
  const int stride = (width + disparity) / 4 + 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      left.at(x, y) = blocks[static_cast<std::size_t>(y / 4) * stride + (x + disparity) / 4];
      right.at(x, y) = blocks[static_cast<std::size_t>(y / 4) * stride + x / 4];
    }

  const auto params = Calibrator::Params::preset("default");
  const CameraInspection camera = inspect_camera(left, right, cameras, target(), params);
  EXPECT_FALSE(camera.report.found);
  EXPECT_EQ(camera.report.failed_stage, "plane") << camera.report.reason;
  EXPECT_FALSE(camera.report.reason.empty());
  ASSERT_TRUE(camera.located.has_value());
  EXPECT_TRUE(camera.located->stereo.found);
  EXPECT_FALSE(camera.circles.has_value() && camera.circles->found);
  EXPECT_NE(
      describe(camera, params, cameras).find("camera  FAILED at " + camera.report.failed_stage),
      std::string::npos);
  EXPECT_EQ(render_camera_inspection(left, camera, cameras, target()).width, width);
}

// The l2s tool beside the test executables (build/l2s, tests in build/tests).
fs::path l2s_binary() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : self.parent_path().parent_path() / "l2s";
}

int run(const std::string& command) {
  const int status = std::system((command + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(FrameInspector, ToolExitCodes) {
  const fs::path l2s = l2s_binary();
  if (l2s.empty() || !fs::exists(l2s)) GTEST_SKIP() << "l2s tool not built";
  test::TempDir dir;
  const std::string dataset = dir.file("dataset");
  simulator_->write(dataset);
  const std::string tool = "'" + l2s.string() + "' detect '" + dataset + "'";

  EXPECT_EQ(run(tool + " --frame 000000 -o '" + dir.file("debug") + "'"), 0);
  EXPECT_TRUE(fs::exists(dir.file("debug/000000_lidar.png")));
  EXPECT_TRUE(fs::exists(dir.file("debug/000000_camera.png")));
  EXPECT_TRUE(fs::exists(dir.file("debug/000000_disparity.png")));

  // Nothing of the scene within 1 m of the lidar: the board cannot be found.
  test::write_text(dir.file("near.yaml"), "lidar_pass_through:\n  max_range: 1.0\n");
  EXPECT_EQ(run(tool + " --sensor lidar --params '" + dir.file("near.yaml") + "' -o '" +
                dir.file("debug") + "'"),
            1);
  EXPECT_EQ(run(tool + " --frame no_such_frame -o '" + dir.file("debug") + "'"), 1);
  EXPECT_EQ(run(tool + " --sensor radar"), 2);
}

}  // namespace
}  // namespace l2s
