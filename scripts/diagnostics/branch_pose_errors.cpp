// Which sensor's board estimate a random scene's error comes from, and in
// which direction (issue 8, accuracy on random scenes). For each seed it
// calibrates the scene as the suite does (default preset, K = 1) and fits,
// per sensor, the rigid motion that takes the true hole centres onto the
// centres the calibration used. The motion is given in the board's own axes:
// tilt about the board's horizontal (x) and vertical (y) axis, spin about its
// normal, shift in the board plane and along the normal. A tilt error of one
// sensor passes one to one into the rotation of the result.
//
// Build from the worktree root after `cmake --build build`:
//   g++ -std=c++17 -O2 -I include -I build/include -I build/generated -I /usr/include/eigen3 \
//     scripts/diagnostics/branch_pose_errors.cpp -o build/branch_pose_errors -L build/src -L build/src/sim \
//     -Wl,-rpath,$PWD/build/src:$PWD/build/src/sim -ll2scalib -ll2scalib_sim
// Usage: build/branch_pose_errors SEED [SEED ...]
#include <l2s/calibrator.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/random_scene.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace {

constexpr double kDeg = 180.0 / M_PI;

// Kabsch: the rigid motion that takes `from` onto `to` (least squares).
Eigen::Isometry3d rigid_fit(const l2s::HoleCenters& from, const l2s::HoleCenters& to) {
  Eigen::Vector3d mean_from = Eigen::Vector3d::Zero(), mean_to = Eigen::Vector3d::Zero();
  for (int h = 0; h < 4; ++h) {
    mean_from += from[h] / 4.0;
    mean_to += to[h] / 4.0;
  }
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int h = 0; h < 4; ++h) H += (from[h] - mean_from) * (to[h] - mean_to).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixV() * svd.matrixU().transpose();
  if (R.determinant() < 0) {
    Eigen::Matrix3d V = svd.matrixV();
    V.col(2) *= -1.0;
    R = V * svd.matrixU().transpose();
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = mean_to - R * mean_from;
  return T;
}

// The error of `found` against `truth`, in the board axes of the true centres
// (x: TL -> TR, y: BL -> TL, z: normal), about their centroid.
void print_error(const char* sensor, const l2s::HoleCenters& truth, const l2s::HoleCenters& found) {
  const Eigen::Vector3d x = (truth[1] - truth[0]).normalized();
  const Eigen::Vector3d y0 = truth[0] - truth[2];
  const Eigen::Vector3d z = x.cross(y0).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R_sensor_board;
  R_sensor_board << x, y, z;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& c : truth) centroid += c / 4.0;
  const Eigen::Isometry3d T = rigid_fit(truth, found);
  const Eigen::AngleAxisd rotation(T.linear());
  const Eigen::Vector3d omega = R_sensor_board.transpose() * rotation.axis() * rotation.angle();
  const Eigen::Vector3d shift = R_sensor_board.transpose() * (T * centroid - centroid);
  double rms = 0.0;
  for (int h = 0; h < 4; ++h) rms += (T * truth[h] - found[h]).squaredNorm() / 4.0;
  std::printf("  %-6s tilt x %+.3f y %+.3f spin %+.3f deg | shift in-plane %+.2f %+.2f normal %+.2f mm | "
              "non-rigid %.2f mm\n",
              sensor, omega.x() * kDeg, omega.y() * kDeg, omega.z() * kDeg, shift.x() * 1e3, shift.y() * 1e3,
              shift.z() * 1e3, std::sqrt(rms) * 1e3);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace l2s;
  for (int a = 1; a < argc; ++a) {
    const std::uint64_t seed = std::strtoull(argv[a], nullptr, 10);
    const sim::RandomScene scene = sim::make_random_scene(seed, 30, 1.0, 0);
    const sim::DatasetSimulator& simulator = *scene.simulator;
    Calibrator calibrator(simulator.cameras(), simulator.config().target, Calibrator::Params::preset("default"));
    for (int i = 0; i < simulator.config().frames; ++i) {
      const sim::SimulatedFrame frame = simulator.frame(i);
      calibrator.add(frame.lidar, frame.left, frame.right, std::to_string(i));
    }
    const Calibrator::Result result = calibrator.result();
    std::printf("seed %llu: %s\n", static_cast<unsigned long long>(seed), scene.summary.c_str());
    if (!result.found) {
      std::printf("  failed: %s\n", result.reason.c_str());
      continue;
    }
    const PoseError error = pose_error(result.T_lidar_camera, simulator.T_lidar_camera());
    std::printf("  result e_t %.2f mm, e_r %.3f deg\n", error.translation * 1e3, error.rotation * kDeg);
    const sim::DatasetSimulator::HoleTruth truth = simulator.true_hole_centers();
    print_error("lidar", truth.lidar, result.lidar_centroids.centers);
    print_error("camera", truth.camera, result.camera_centroids.centers);
  }
}
