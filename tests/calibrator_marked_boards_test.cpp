// A stereo board whose face is printed (speckle, noise print: what stereo
// users print so that SGM has something to match) and that carries the
// target's markers: where the stereo search loses the board against its
// surroundings, its markers in both images give the pose.

#include <l2s/calibrator.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace l2s {
namespace {

struct PrintedCase {
  const char* name;
  int setting;
  sim::BoardTexture face;
};

class CalibratorMarkedBoards : public ::testing::TestWithParam<PrintedCase> {};

int camera_frames(const sim::DatasetSimulator& simulator, const Calibrator::Params& params,
                  Calibrator::Result* result = nullptr) {
  Calibrator calibrator(simulator.cameras(), simulator.config().target, params);
  for (int i = 0; i < simulator.config().frames; ++i) {
    const sim::SimulatedFrame frame = simulator.frame(i);
    calibrator.add(frame.lidar, frame.left, frame.right);
  }
  const Calibrator::Result r = calibrator.result();
  if (result) *result = r;
  return r.camera_frames;
}

TEST_P(CalibratorMarkedBoards, APrintedFaceIsFoundByItsMarkersWhereStereoLosesIt) {
  sim::SimulationConfig config = sim::SimulationConfig::paper(GetParam().setting, "vlp16");
  config.frames = 3;
  config.seed = 3;
  config.target = Target::with_default_markers();
  config.appearance.board = GetParam().face;
  const sim::DatasetSimulator simulator(config);

  Calibrator::Params stereo_alone = Calibrator::Params::preset("default");
  stereo_alone.board_from_markers = false;
  EXPECT_LT(camera_frames(simulator, stereo_alone), config.frames) << "the stereo search alone loses a frame";

  Calibrator::Result result;
  EXPECT_EQ(camera_frames(simulator, Calibrator::Params::preset("default"), &result), config.frames);
  ASSERT_TRUE(result.found) << result.reason;
  const PoseError error = pose_error(result.T_lidar_camera, simulator.T_lidar_camera());
  EXPECT_LT(error.translation * 1e3, 15.0) << "[mm]";
  EXPECT_LT(error.rotation * 180.0 / M_PI, 0.3) << "[deg]";
}

INSTANTIATE_TEST_SUITE_P(Faces, CalibratorMarkedBoards,
                         ::testing::Values(PrintedCase{"NoisePrint", 1, sim::BoardTexture::NoisePrint},
                                           PrintedCase{"Speckle", 3, sim::BoardTexture::Speckle}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace l2s
