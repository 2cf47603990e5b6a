// Where the camera branch's K = 0 error comes from (issue 8, "bias floor").
// For each paper setting (VLP-16, K = 0, one frame: noise-free frames are
// identical) it runs the BoardPoseRefiner from the TRUE board pose and prints
// the pose it converges to: the refiner's fixed point on these images. The
// default pipeline ends at the same pose to 1e-3 mm, so this isolates the
// image/edge part of the error from detection, initialisation and the lidar.
//
// Build from the worktree root after `cmake --build build`:
//   g++ -std=c++17 -O2 -I include -I build/include -I build/generated -I /usr/include/eigen3 \
//     scripts/diagnostics/camera_bias_floor.cpp -o build/camera_bias_floor -L build/src -L build/src/sim \
//     -Wl,-rpath,$PWD/build/src:$PWD/build/src/sim -ll2scalib -ll2scalib_sim
// Usage: build/camera_bias_floor [first_setting last_setting [board_thickness_m]]
#include <l2s/board_pose_refiner.hpp>
#include <l2s/calibrator.hpp>
#include <l2s/sim/simulation.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  using namespace l2s;
  const int first = argc > 2 ? std::atoi(argv[1]) : 1, last = argc > 2 ? std::atoi(argv[2]) : 9;
  for (int setting = first; setting <= last; ++setting) {
    auto config = sim::SimulationConfig::paper(setting, "vlp16");
    config.noise_factor = 0.0;
    config.frames = 1;
    config.seed = 3;
    config.threads = 1;
    if (argc > 3) config.target.board_thickness = std::atof(argv[3]);
    const sim::DatasetSimulator simulator(config);
    const Eigen::Isometry3d T_camera_board =
        config.rig.T_cambody_optical(0).inverse() * simulator.scene().T_cambody_board;
    const sim::SimulatedFrame frame = simulator.frame(0);
    const BoardPoseRefiner refiner(Calibrator::Params::preset("default").board_refiner);
    const BoardPoseRefiner::Result r =
        refiner.refine(frame.left, frame.right, simulator.cameras(), config.target, T_camera_board);
    const Eigen::AngleAxisd error(T_camera_board.linear().transpose() * r.T_camera_board.linear());
    std::printf("setting %d: converged %d, rim rms %.4f px, %d samples, rotation error %.4f deg\n", setting,
                r.converged, r.rms_px, r.samples, error.angle() * 180.0 / M_PI);
    const auto holes = config.target.hole_centers();
    for (int h = 0; h < 4; ++h) {
      const Eigen::Vector3d truth = T_camera_board * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0);
      const Eigen::Vector3d e = 1e3 * (r.centers[h] - truth);
      std::printf("  hole %d (%+.2f %+.2f %.2f m): error [mm] %+.3f %+.3f %+.3f\n", h, truth.x(), truth.y(),
                  truth.z(), e.x(), e.y(), e.z());
    }
  }
}
