#include "pose_printing.hpp"

#include <l2s/fit_uncertainty.hpp>
#include <l2s/pose.hpp>

namespace l2s::cli {

void print_pose(const char* label, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.rotation());
  std::printf("%-10s t = (%8.4f, %8.4f, %8.4f) m   rpy = (%8.4f, %8.4f, %8.4f) rad\n", label, t.x(), t.y(), t.z(),
              rpy[0], rpy[1], rpy[2]);
}

void print_uncertainty(const JointRegistrar::Result& joint, const std::vector<bool>& used) {
  const FitUncertainty& u = joint.uncertainty;
  if (!u.valid) return;
  std::printf("uncertainty (1 sigma / 95 %%, from %d residual dof):\n ", u.dof);
  for (int k = 0; k < 6; ++k) {
    const double unit = k < 3 ? 1e3 : 180.0 / M_PI;
    std::printf(" %s %.2f/%.2f %s", dof_names()[k], u.sigma[k] * unit, u.bound_95[k] * unit, k < 3 ? "mm" : "deg");
  }
  std::printf("\n");
  for (std::size_t k = 0, n = 0; k < used.size(); ++k) {
    if (!used[k] || n >= joint.leave_one_out.size()) continue;
    const auto& loo = joint.leave_one_out[n++];
    std::printf("  without pose %zu: moves %.2f mm, %.3f deg\n", k, loo.translation * 1e3, loo.rotation * 180.0 / M_PI);
  }
  if (!u.suggestion.empty())
    std::printf("advice    the fit is poorly conditioned (condition %.1f, weakest: %s): add a pose %s\n", u.condition,
                u.weakest_summary.c_str(), u.suggestion.c_str());
}

}  // namespace l2s::cli
