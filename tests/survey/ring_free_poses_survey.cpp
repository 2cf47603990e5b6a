// Survey of a ring-free lidar beside a camera while the board is moved
// through three static poses: not a test, a measurement (roadmap C step 2).
// Scene i of COUNT (from FIRST_SEED on): Mid-360-like for even i, Avia-like
// for odd; the random scenes' lidar draw with the board 2-4 m away, three
// poses of 10 frames with two frames of the board on its way between them,
// beside the stereo pair (stereo) or its left camera alone, the board
// carrying markers (mono). Prints one line per scene (lidar detections,
// verdict, e_t, e_r) and the share calibrated with the median errors.
//
//   ring_free_poses_survey stereo|mono FIRST_SEED COUNT

#include "lidar_survey_scene.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/multi_pose.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

double median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 || (std::string(argv[1]) != "stereo" && std::string(argv[1]) != "mono")) {
    std::fprintf(stderr, "usage: ring_free_poses_survey stereo|mono FIRST_SEED COUNT\n");
    return 2;
  }
  const bool mono = std::string(argv[1]) == "mono";
  const std::uint64_t first = std::strtoull(argv[2], nullptr, 10);
  const int count = std::atoi(argv[3]);
  int calibrated = 0, done = 0;
  std::vector<double> e_t, e_r;
  for (int i = 0; i < count; ++i) {
    const std::string model = i % 2 == 0 ? "mid360" : "avia";
    const std::uint64_t seed = first + static_cast<std::uint64_t>(i);
    const auto drawn = l2s::survey::make_lidar_scene(model, seed, 10, 2.0, 4.0);
    if (!drawn) {
      std::printf("%2d %-6s no scene\n", i, model.c_str());
      continue;
    }
    l2s::sim::MultiPoseConfig config;
    config.base = drawn->config();
    config.base.frames = 10;
    config.base.mono = mono;
    if (mono) config.base.target = l2s::Target::with_default_markers();
    config.poses = 3;
    config.moving_frames = 2;
    std::unique_ptr<l2s::sim::MultiPoseSimulator> simulator;
    try {
      simulator = std::make_unique<l2s::sim::MultiPoseSimulator>(config);
    } catch (const l2s::Error& error) {
      std::printf("%2d %-6s no poses: %s\n", i, model.c_str(), error.what());
      continue;
    }
    const l2s::StereoCamera cameras = simulator->cameras();
    l2s::Calibrator calibrator = mono ? l2s::Calibrator(cameras.left, cameras.images, config.base.target)
                                      : l2s::Calibrator(cameras, config.base.target);
    for (int f = 0; f < simulator->frames(); ++f) {
      const auto frame = simulator->frame(f);
      if (mono)
        calibrator.add(frame.lidar, frame.left);
      else
        calibrator.add(frame.lidar, frame.left, frame.right);
    }
    const l2s::Calibrator::Result result = calibrator.result();
    const bool ok = result.found && result.quality.verdict != l2s::CalibrationCheck::Verdict::Failed;
    const l2s::PoseError error =
        result.found ? l2s::pose_error(result.T_lidar_camera, simulator->T_lidar_camera()) : l2s::PoseError{};
    ++done;
    calibrated += ok;
    if (ok) {
      e_t.push_back(error.translation);
      e_r.push_back(error.rotation);
    }
    const char* verdicts[] = {"ok", "suspect", "failed"};
    std::printf("%2d %-6s poses %zu lidar %2d camera %2d of %2d | %s %s e_t %7.1f mm e_r %.3f deg%s%s\n", i,
                model.c_str(), simulator->poses().size(), result.lidar_frames, result.camera_frames,
                result.frames_added, result.found ? "found" : "no result",
                result.found ? verdicts[static_cast<int>(result.quality.verdict)] : "", error.translation * 1e3,
                error.rotation * 180.0 / M_PI, result.found ? "" : " | ",
                result.found ? "" : result.reason.substr(0, 160).c_str());
    std::fflush(stdout);
  }
  std::printf("%s: calibrated (a result, check not failed) %d of %d; median e_t %.1f mm, e_r %.3f deg\n", argv[1],
              calibrated, done, median(e_t) * 1e3, median(e_r) * 180.0 / M_PI);
  return 0;
}
