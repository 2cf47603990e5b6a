// Uncertainty of a rigid fit to point pairs (Gauss-Newton linearisation at the
// estimate): residuals r_i = target_i - T(theta) source_i with
// theta = (tx, ty, tz, roll, pitch, yaw) as reported to users; the Jacobian
// is taken by central differences, so it matches that parametrisation
// exactly. covariance = s^2 (J^T J)^-1, s^2 = |r|^2 / (3 n - 6).
// Conditioning: the eigen-decomposition of J^T J with rotations expressed as
// the motion they cause at the points' mean range, so that metres and radians
// compare; its weakest eigenvector is the motion the poses fix least, and the
// suggested pose is the candidate (moved or turned copy of the present
// board) whose points move most along it.

#include <l2s/fit_uncertainty.hpp>

#include <l2s/pose.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace l2s {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

Eigen::Isometry3d pose_of(const Vector6d& theta) {
  return pose_from_roll_pitch_yaw(theta[3], theta[4], theta[5], theta.head<3>());
}

/// d(T(theta) p)/d theta, 3 x 6, by central differences.
Eigen::Matrix<double, 3, 6> point_jacobian(const Vector6d& theta, const Eigen::Vector3d& p) {
  constexpr double h = 1e-6;
  Eigen::Matrix<double, 3, 6> J;
  for (int k = 0; k < 6; ++k) {
    Vector6d plus = theta, minus = theta;
    plus[k] += h;
    minus[k] -= h;
    J.col(k) = (pose_of(plus) * p - pose_of(minus) * p) / (2.0 * h);
  }
  return J;
}

/// Information a set of source points adds along `direction` (scaled units).
double information_along(const Vector6d& theta, const std::vector<Eigen::Vector3d>& source,
                         const Vector6d& direction_unscaled) {
  double sum = 0.0;
  for (const auto& p : source) sum += (point_jacobian(theta, p) * direction_unscaled).squaredNorm();
  return sum;
}

struct Candidate {
  const char* words;
  Eigen::Isometry3d motion;  ///< applied to the board's points in the target frame
};

/// Moved and turned copies of the board about its centre `c` (target frame,
/// x forward, y left, z up as for a lidar).
std::vector<Candidate> candidates(const Eigen::Vector3d& c) {
  const Eigen::Vector3d forward = Eigen::Vector3d(c.x(), c.y(), 0.0).normalized();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d left = up.cross(forward);
  const auto shift = [](const Eigen::Vector3d& d) { return Eigen::Isometry3d(Eigen::Translation3d(d)); };
  const auto turn = [&](const Eigen::Vector3d& axis, double angle) {
    return Eigen::Isometry3d(Eigen::Translation3d(c) * Eigen::AngleAxisd(angle, axis) * Eigen::Translation3d(-c));
  };
  return {{"farther away", shift(1.0 * forward)},
          {"nearer", shift(-1.0 * forward)},
          {"to the left", shift(1.0 * left)},
          {"to the right", shift(-1.0 * left)},
          {"higher", shift(0.5 * up)},
          {"lower", shift(-0.5 * up)},
          {"turned about the vertical", turn(up, 0.5)},
          {"tilted back", turn(left, 0.35)}};
}

std::string describe(const Vector6d& v) {
  std::ostringstream out;
  int shown = 0;
  for (int k = 0; k < 6; ++k)
    if (std::abs(v[k]) >= 0.3) out << (shown++ ? " with " : "") << dof_names()[k];
  return out.str();
}

}  // namespace

const std::array<const char*, 6>& dof_names() {
  static const std::array<const char*, 6> names{"tx", "ty", "tz", "roll", "pitch", "yaw"};
  return names;
}

double student_t_95(int dof) {
  static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                 2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                 2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return std::numeric_limits<double>::infinity();
  if (dof <= 30) return table[dof - 1];
  return 1.95996 + 2.4 / dof;  // within 0.002 of the true quantile above 30
}

void add_shared_group_error(FitUncertainty& u, const Eigen::Isometry3d& T_target_source,
                            const std::vector<std::vector<Eigen::Vector3d>>& source_groups, double sigma_t,
                            double sigma_r) {
  if (!(sigma_t > 0.0 || sigma_r > 0.0)) return;
  Vector6d motion_variance;
  motion_variance << Eigen::Vector3d::Constant(sigma_t * sigma_t), Eigen::Vector3d::Constant(sigma_r * sigma_r);
  add_shared_group_error(u, T_target_source, source_groups,
                         std::vector<MotionCovariance>(source_groups.size(), motion_variance.asDiagonal()));
}

void add_shared_group_error(FitUncertainty& u, const Eigen::Isometry3d& T_target_source,
                            const std::vector<std::vector<Eigen::Vector3d>>& source_groups,
                            const std::vector<MotionCovariance>& motion_covariances) {
  if (!u.valid || motion_covariances.size() != source_groups.size()) return;
  Vector6d theta;
  theta << T_target_source.translation(), roll_pitch_yaw(T_target_source.rotation());
  // theta moves by (J^T J)^-1 J^T dr for residual changes dr; a group moved
  // by (dt, dphi) about its centroid c changes its residuals by
  // dt + dphi x (q - c) (target frame, q = T source), i.e. G (dt, dphi).
  struct Group {
    Eigen::MatrixXd J, G;
    MotionCovariance motion;
  };
  std::vector<Group> groups;
  Matrix6d JtJ = Matrix6d::Zero();
  for (std::size_t g = 0; g < source_groups.size(); ++g) {
    std::vector<Eigen::Vector3d> s;  // the group's finite points
    for (const auto& p : source_groups[g])
      if (p.allFinite()) s.push_back(p);
    if (s.empty()) continue;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& p : s) c += T_target_source * p / static_cast<double>(s.size());
    Eigen::MatrixXd J(3 * s.size(), 6), G(3 * s.size(), 6);
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Eigen::Vector3d lever = T_target_source * s[i] - c;
      J.block<3, 6>(3 * i, 0) = point_jacobian(theta, s[i]);
      G.block<3, 3>(3 * i, 0).setIdentity();
      G.block<3, 3>(3 * i, 3) << 0, lever.z(), -lever.y(), -lever.z(), 0, lever.x(), lever.y(), -lever.x(), 0;
    }
    JtJ += J.transpose() * J;
    groups.push_back({std::move(J), std::move(G), motion_covariances[g]});
  }
  const Eigen::FullPivLU<Matrix6d> lu(JtJ);
  if (!lu.isInvertible()) return;
  const Matrix6d JtJ_inverse = lu.inverse();
  Matrix6d shared = Matrix6d::Zero();
  for (const Group& group : groups) {
    const Matrix6d M = JtJ_inverse * group.J.transpose() * group.G;
    shared += M * group.motion * M.transpose();
  }
  const double t95 = student_t_95(u.dof);
  u.covariance += shared;
  for (int k = 0; k < 6; ++k) {
    const double residual_sigma = std::sqrt(std::max(0.0, u.sigma[k] * u.sigma[k] - u.sigma_shared[k] * u.sigma_shared[k]));
    u.sigma_shared[k] = std::sqrt(std::max(0.0, u.sigma_shared[k] * u.sigma_shared[k] + shared(k, k)));
    u.sigma[k] = std::hypot(residual_sigma, u.sigma_shared[k]);
    u.bound_95[k] = std::hypot(t95 * residual_sigma, 1.95996 * u.sigma_shared[k]);
  }
}

double translation_bound_95(const FitUncertainty& u) {
  if (!u.valid) return 0.0;
  return Eigen::Vector3d(u.bound_95[0], u.bound_95[1], u.bound_95[2]).norm();
}

double rotation_bound_95(const FitUncertainty& u, const Eigen::Isometry3d& T_target_source) {
  if (!u.valid) return 0.0;
  // The bounds with the covariance's correlations between roll, pitch and yaw.
  const Eigen::Matrix3d C = u.covariance.bottomRightCorner<3, 3>();
  Eigen::Matrix3d bounds = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double norm = std::sqrt(C(i, i) * C(j, j));
      const double correlation = norm > 0.0 ? C(i, j) / norm : (i == j ? 1.0 : 0.0);
      bounds(i, j) = correlation * u.bound_95[3 + i] * u.bound_95[3 + j];
    }
  // d(rotation vector) / d(roll, pitch, yaw), by central differences.
  const Eigen::Vector3d rpy = roll_pitch_yaw(T_target_source.rotation());
  const auto rotation = [](const Eigen::Vector3d& a) -> Eigen::Matrix3d {  // a copy: linear() views a temporary
    return pose_from_roll_pitch_yaw(a[0], a[1], a[2], Eigen::Vector3d::Zero()).linear();
  };
  constexpr double h = 1e-6;
  Eigen::Matrix3d J;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d plus = rpy, minus = rpy;
    plus[k] += h;
    minus[k] -= h;
    const Eigen::AngleAxisd turn(rotation(plus) * rotation(minus).transpose());
    J.col(k) = turn.axis() * turn.angle() / (2.0 * h);
  }
  return std::sqrt(std::max(0.0, (J * bounds * J.transpose()).trace()));
}

double prediction_rms(const FitUncertainty& u, const Eigen::Isometry3d& T_target_source,
                      const std::vector<Eigen::Vector3d>& source) {
  if (!u.valid || source.empty()) return 0.0;
  Vector6d theta;
  theta << T_target_source.translation(), roll_pitch_yaw(T_target_source.rotation());
  double sum = 0.0;
  for (const auto& p : source) {
    const Eigen::Matrix<double, 3, 6> J = point_jacobian(theta, p);
    sum += 3.0 * u.sigma_residual * u.sigma_residual + (J * u.covariance * J.transpose()).trace();
  }
  return std::sqrt(sum / source.size());
}

FitUncertainty fit_uncertainty(const std::vector<Eigen::Vector3d>& target, const std::vector<Eigen::Vector3d>& source,
                               const Eigen::Isometry3d& T_target_source) {
  FitUncertainty out;
  std::vector<Eigen::Vector3d> t, s;
  for (std::size_t i = 0; i < std::min(target.size(), source.size()); ++i)
    if (target[i].allFinite() && source[i].allFinite()) t.push_back(target[i]), s.push_back(source[i]);
  out.pairs = static_cast<int>(t.size());
  out.dof = 3 * out.pairs - 6;
  if (out.dof < 1) {
    out.reason = "too few point pairs";
    return out;
  }
  const Eigen::Vector3d rpy = roll_pitch_yaw(T_target_source.rotation());
  Vector6d theta;
  theta << T_target_source.translation(), rpy;
  Matrix6d JtJ = Matrix6d::Zero();
  double ssr = 0.0, mean_range = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Eigen::Matrix<double, 3, 6> J = point_jacobian(theta, s[i]);
    JtJ += J.transpose() * J;
    ssr += (t[i] - T_target_source * s[i]).squaredNorm();
    mean_range += t[i].norm() / t.size();
  }
  Vector6d scale;
  scale << 1, 1, 1, mean_range, mean_range, mean_range;
  const Matrix6d scaled = scale.cwiseInverse().asDiagonal() * JtJ * scale.cwiseInverse().asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(scaled);
  const double lambda_min = eig.eigenvalues()[0], lambda_max = eig.eigenvalues()[5];
  if (!(lambda_min > 1e-12 * lambda_max) || std::abs(std::cos(rpy[1])) < 1e-6) {
    out.reason = "the pairs do not fix all six degrees of freedom";
    return out;
  }
  out.sigma_residual = std::sqrt(ssr / out.dof);
  out.covariance = out.sigma_residual * out.sigma_residual * JtJ.inverse();
  const double t95 = student_t_95(out.dof);
  for (int k = 0; k < 6; ++k) {
    out.sigma[k] = std::sqrt(std::max(0.0, out.covariance(k, k)));
    out.bound_95[k] = t95 * out.sigma[k];
  }
  out.condition = std::sqrt(lambda_max / lambda_min);
  out.weakest = eig.eigenvectors().col(0);
  if (out.weakest.cwiseAbs().maxCoeff() != out.weakest.maxCoeff()) out.weakest = -out.weakest;
  out.weakest_summary = describe(out.weakest);

  // Which extra board would move most along the weakest direction.
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  for (const auto& p : t) center += p / static_cast<double>(t.size());
  const Vector6d direction = scale.cwiseInverse().asDiagonal() * out.weakest;
  // The candidate boards are copies of the first (four points) centred on
  // the centre of all poses, then moved or turned.
  const std::size_t board = std::min<std::size_t>(4, t.size());
  Eigen::Vector3d first_center = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < board; ++i) first_center += T_target_source * s[i] / static_cast<double>(board);
  double best = -1.0;
  for (const Candidate& candidate : candidates(center)) {
    std::vector<Eigen::Vector3d> moved;
    for (std::size_t i = 0; i < board; ++i)
      moved.push_back(T_target_source.inverse() *
                      (candidate.motion * (T_target_source * s[i] - first_center + center)));
    const double gain = information_along(theta, moved, direction);
    if (gain > best) best = gain, out.suggestion = candidate.words;
  }
  out.valid = true;
  return out;
}

}  // namespace l2s
