#include "calibrator/board_plane_refinement.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace l2s::detail {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Jacobian = Eigen::Matrix<double, 3, 6>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

/// Normal equations of the residuals at T; the update is a left rotation
/// exp(w) and a translation step: R <- exp(w) R, t <- t + dt, with (w, dt).
struct Normal {
  Matrix6 H = Matrix6::Zero();
  Vector6 g = Vector6::Zero();

  void add(const Jacobian& J, const Eigen::Vector3d& r, double sigma) {
    const double w = 1.0 / (sigma * sigma);
    H += w * J.transpose() * J;
    g += w * J.transpose() * r;
  }
  void add(const Jacobian& J, const Eigen::Vector3d& r, const Eigen::Matrix3d& information) {
    H += J.transpose() * information * J;
    g += J.transpose() * information * r;
  }
  void add(const Vector6& J, double r, double sigma) {
    const double w = 1.0 / (sigma * sigma);
    H += w * J * J.transpose();
    g += w * J * r;
  }
};

Normal normal_equations(const Eigen::Isometry3d& T, const std::vector<BoardPoseObservation>& poses,
                        const BoardPlaneWeights& weights) {
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d t = T.translation();
  Normal n;
  for (const BoardPoseObservation& pose : poses) {
    for (int h = 0; h < 4; ++h) {  // r = c_target - (R c_source + t)
      const Eigen::Vector3d Rc = R * pose.source[h];
      Jacobian J;
      J << skew(Rc), -Eigen::Matrix3d::Identity();
      const Eigen::Vector3d sight = R * pose.source[h].normalized();
      const double across = weights.centre_sigma, along = weights.source_depth_sigma;
      const Eigen::Matrix3d covariance =
          across * across * Eigen::Matrix3d::Identity() + along * along * sight * sight.transpose();
      n.add(J, pose.target[h] - Rc - t, Eigen::Matrix3d(covariance.inverse()));
    }
    const Eigen::Vector3d Rn = R * pose.plane_source.normal();
    Jacobian J;  // r = n_target - R n_source
    J << skew(Rn), Eigen::Matrix3d::Zero();
    n.add(J, pose.plane_target.normal() - Rn, weights.normal_sigma);
    // The source plane in the target frame has offset d_source - (R n)·t: r = d_target - that.
    Vector6 j;
    j << Rn.cross(t), Rn;
    n.add(j, pose.plane_target.offset() - pose.plane_source.offset() + Rn.dot(t), weights.offset_sigma);
  }
  return n;
}

}  // namespace

Eigen::Isometry3d refine_with_board_planes(const Eigen::Isometry3d& T0,
                                           const std::vector<BoardPoseObservation>& poses,
                                           const BoardPlaneWeights& weights) {
  Eigen::Isometry3d T = T0;
  for (int k = 0; k < weights.iterations && !poses.empty(); ++k) {
    const Normal n = normal_equations(T, poses, weights);
    const Eigen::LDLT<Matrix6> solver(n.H);
    if (solver.info() != Eigen::Success || !solver.isPositive()) return T0;
    const Vector6 step = -solver.solve(n.g);
    if (!step.allFinite()) return T0;
    const Eigen::Vector3d w = step.head<3>();
    const Eigen::Matrix3d dR =
        w.norm() > 0.0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity();
    T.linear() = dR * T.linear();
    T.translation() += step.tail<3>();
    if (step.norm() < 1e-12) break;
  }
  return T;
}

Plane mean_plane(const std::vector<Plane>& planes) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double offset = 0.0;
  for (const Plane& p : planes) {
    normal += p.normal();
    offset += p.offset();
  }
  if (planes.empty() || normal.norm() == 0.0) return Plane(Eigen::Vector3d::UnitX(), 0.0);
  return Plane(normal.normalized(), offset / static_cast<double>(planes.size()));
}

}  // namespace l2s::detail
