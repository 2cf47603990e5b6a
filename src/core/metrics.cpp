#include <l2s/metrics.hpp>

#include <algorithm>
#include <cmath>

namespace l2s {

PoseError pose_error(const Eigen::Isometry3d& T_estimate, const Eigen::Isometry3d& T_true) {
  PoseError error;
  error.translation = (T_estimate.translation() - T_true.translation()).norm();
  const Eigen::Matrix3d R_delta = T_estimate.rotation().transpose() * T_true.rotation();
  // acos of the trace is ill-conditioned near zero; the axis-angle norm is not.
  error.rotation = Eigen::AngleAxisd(R_delta).angle();
  return error;
}

}  // namespace l2s
