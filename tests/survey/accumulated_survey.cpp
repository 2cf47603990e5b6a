// Survey of `lidar: accumulated` calibration over random lidar scenes: not a
// test, a measurement. Dataset i of COUNT (from FIRST_SEED on): Mid-360 for
// even i, Avia for odd; 1 + i % 5 seconds of returns as one cloud, cropped to
// 0.5 m around the board for every other pair, the whole cloud otherwise;
// the scenes experiment's lidar draw with the board 2-5 m away, beside 10
// stereo frames (default rig). The cloud is detected once
// (Calibrator::detect_accumulated) and paired with every frame. Prints one
// line per dataset (found, verdict, e_t, e_r, worst lidar hole centre error
// against ground truth) and the shares the acceptance of roadmap C step 1b
// asks for.
//
//   accumulated_survey FIRST_SEED COUNT

#include "lidar_survey_scene.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/simulation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: accumulated_survey FIRST_SEED COUNT\n");
    return 2;
  }
  const std::uint64_t first = std::strtoull(argv[1], nullptr, 10);
  const int count = std::atoi(argv[2]);
  constexpr int kFrames = 10;
  int calibrated = 0, centres_within = 0, done = 0;
  for (int i = 0; i < count; ++i) {
    const std::string model = i % 2 == 0 ? "mid360" : "avia";
    const double seconds = 1.0 + i % 5;
    const double crop = (i / 2) % 2 == 1 ? 0.5 : 0.0;
    const auto drawn = l2s::survey::make_lidar_scene(model, first + static_cast<std::uint64_t>(i), kFrames, 2.0, 5.0);
    if (!drawn) {
      std::printf("%2d %-6s no scene\n", i, model.c_str());
      continue;
    }
    l2s::sim::SimulationConfig config = drawn->config();
    config.board_pose = drawn->board_pose();
    config.accumulated_seconds = seconds;
    config.accumulated_crop = crop;
    const l2s::sim::DatasetSimulator simulator(config);
    l2s::Calibrator calibrator(simulator.cameras(), config.target);
    const l2s::AccumulatedLidar cloud = calibrator.detect_accumulated(simulator.accumulated_cloud());
    double worst = -1.0;
    if (cloud.report().found) {
      const auto truth = simulator.true_hole_centers().lidar;
      worst = 0.0;
      for (int h = 0; h < 4; ++h) worst = std::max(worst, (cloud.report().centers[h] - truth[h]).norm());
    }
    for (int f = 0; f < kFrames; ++f) {
      const auto frame = simulator.frame(f);
      calibrator.add(cloud, frame.left, frame.right);
    }
    const l2s::Calibrator::Result result = calibrator.result();
    const bool ok = result.found && result.quality.verdict != l2s::CalibrationCheck::Verdict::Failed;
    const l2s::PoseError error =
        result.found ? l2s::pose_error(result.T_lidar_camera, simulator.T_lidar_camera()) : l2s::PoseError{};
    ++done;
    calibrated += ok;
    centres_within += worst >= 0.0 && worst <= 0.005;
    const char* verdicts[] = {"ok", "suspect", "failed"};
    std::printf("%2d %-6s %.0f s %-8s lidar %-5s worst centre %6.1f mm | %s %s e_t %6.1f mm e_r %.3f deg%s%s\n", i,
                model.c_str(), seconds, crop > 0 ? "cropped" : "whole", cloud.report().found ? "found" : "lost",
                worst * 1e3, result.found ? "found" : "no result",
                result.found ? verdicts[static_cast<int>(result.quality.verdict)] : "", error.translation * 1e3,
                error.rotation * 180.0 / M_PI, cloud.report().found ? "" : " | ",
                cloud.report().found ? "" : cloud.report().reason.substr(0, 160).c_str());
    std::fflush(stdout);
  }
  std::printf("calibrated (a result, check not failed): %d of %d; lidar centres within 5 mm: %d of %d\n", calibrated,
              done, centres_within, done);
  return 0;
}
