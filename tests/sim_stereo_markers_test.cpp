// Boards as users make them, in both cameras: the target's ArUco markers of
// any dictionary on a stereo board, found by OpenCV's detector where the
// ground truth puts them in both rectified images; a board of another size
// and hole layout (1.2 x 0.9 m, r 0.10 m on 0.60 x 0.45 m, markers of its
// own) makes a dataset the contract accepts, its holes where the truth is.

#include <l2s/sim/simulation.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <utility>

namespace l2s::sim {
namespace {

cv::Mat gray_of(const Image& image) {
  cv::Mat mat(image.height, image.width, image.channels == 1 ? CV_8UC1 : CV_8UC3,
              const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat gray;
  if (image.channels == 1)
    gray = mat.clone();
  else
    cv::cvtColor(mat, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

TEST(StereoMarkers, FoundInBothRectifiedImagesWithinHalfAPixelOfTheTruth) {
  for (const auto& [dictionary, opencv_name] :
       {std::pair<std::string, cv::aruco::PREDEFINED_DICTIONARY_NAME>{"DICT_4X4_50", cv::aruco::DICT_4X4_50},
        {"DICT_5X5_100", cv::aruco::DICT_5X5_100},
        {"DICT_6X6_250", cv::aruco::DICT_6X6_250},
        {"DICT_7X7_100", cv::aruco::DICT_7X7_100}}) {
    SCOPED_TRACE(dictionary);
    SimulationConfig config = SimulationConfig::paper(1, "vlp16");
    config.frames = 1;
    config.seed = 5;
    config.target = Target::with_default_markers();
    config.target.markers->dictionary = dictionary;
    config.target.markers->ids = {3, 17, 28, 41};
    const DatasetSimulator simulator(config);
    ASSERT_FALSE(simulator.config().rig.images() == ImageKind::Raw);
    const SimulatedFrame frame = simulator.frame(0);
    const Eigen::Isometry3d T_cambody_board = simulator.board_pose().T_cambody_board();
    const MarkerLayout& layout = *config.target.markers;

    const auto aruco = cv::aruco::getPredefinedDictionary(opencv_name);
    const auto params = cv::aruco::DetectorParameters::create();
    params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
    for (int camera = 0; camera < 2; ++camera) {
      SCOPED_TRACE(camera ? "right" : "left");
      std::vector<std::vector<cv::Point2f>> corners;
      std::vector<int> ids;
      cv::aruco::detectMarkers(gray_of(camera ? frame.right : frame.left), aruco, corners, ids, params);
      double worst = 0.0;
      for (std::size_t m = 0; m < layout.ids.size(); ++m) {
        const auto found = std::find(ids.begin(), ids.end(), layout.ids[m]);
        ASSERT_TRUE(found != ids.end()) << "marker " << layout.ids[m] << " not found";
        const auto& image_corners = corners[static_cast<std::size_t>(found - ids.begin())];
        const auto board_corners = layout.corners(m);
        for (std::size_t c = 0; c < 4; ++c) {
          const Eigen::Vector2d truth = simulator.config().rig.project(camera, T_cambody_board * board_corners[c]);
          worst = std::max(worst, (Eigen::Vector2d(image_corners[c].x, image_corners[c].y) - truth).norm());
        }
      }
      EXPECT_LT(worst, 0.5) << "[px] worst corner";
    }
  }
}

Target board_of_its_own() {
  Target target;
  target.board_width = 1.2;
  target.board_height = 0.9;
  target.hole_radius = 0.10;
  target.hole_spacing_x = 0.60;
  target.hole_spacing_y = 0.45;
  MarkerLayout markers;
  markers.dictionary = "DICT_5X5_100";
  markers.size = 0.15;
  markers.ids = {0, 1, 2, 3};
  markers.centres = {Eigen::Vector2d(-0.49, 0.34), Eigen::Vector2d(0.49, 0.34), Eigen::Vector2d(-0.49, -0.34),
                     Eigen::Vector2d(0.49, -0.34)};
  target.markers = markers;
  return target;
}

TEST(OtherBoards, ABoardOfItsOwnSizeMakesAValidDatasetWithItsHolesWhereTheTruthIs) {
  SimulationConfig config = SimulationConfig::paper(2, "vlp16");
  config.frames = 1;
  config.seed = 9;
  config.target = board_of_its_own();
  ASSERT_NO_THROW(config.target.validate());
  const DatasetSimulator simulator(config);

  // The holes: each centre's pixel sees through the board, a point on the
  // board between the hole and the board's centre does not.
  StereoRenderer::Params params;
  const CleanImage image = StereoRenderer(simulator.config().rig, params)
                               .render_camera(RayCaster(make_scene(config.target, simulator.board_pose())), 0);
  const Eigen::Isometry3d T_cambody_board = simulator.board_pose().T_cambody_board();
  for (const Eigen::Vector2d& centre : config.target.hole_centers()) {
    const Eigen::Vector2d hole =
        simulator.config().rig.project(0, T_cambody_board * Eigen::Vector3d(centre.x(), centre.y(), 0.0));
    const Eigen::Vector2d beside_xy = centre * (1.0 - 1.5 * config.target.hole_radius / centre.norm());
    const Eigen::Vector2d beside =
        simulator.config().rig.project(0, T_cambody_board * Eigen::Vector3d(beside_xy.x(), beside_xy.y(), 0.0));
    EXPECT_NE(image.surface_at(static_cast<int>(std::lround(hole.x())), static_cast<int>(std::lround(hole.y()))),
              SurfaceId::Board);
    EXPECT_EQ(image.surface_at(static_cast<int>(std::lround(beside.x())), static_cast<int>(std::lround(beside.y()))),
              SurfaceId::Board);
  }

  const test::TempDir dir;
  simulator.write(dir.path() + "/dataset");
  L2S_NEED_DATASET_CHECKER();
  const std::string command =
      "/usr/bin/python3 " + test::dataset_checker() + " " + dir.path() + "/dataset --lidar-beams 16 >/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

}  // namespace
}  // namespace l2s::sim
