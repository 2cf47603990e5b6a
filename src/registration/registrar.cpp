// Registration of the labelled hole centroids (paper Sec. III-D).
// Step 1, as in the paper: the rotation-free translation t' as least-squares
// solution of the 12 equations t = p_l^i - p_c^i, by column-pivoting QR.
// Step 2: the full rigid transform between the lidar points and the
// translated camera points. The paper runs ICP here; with the four labelled
// correspondences known, ICP's first iteration already is the closed-form
// least-squares rigid fit (Kabsch/Umeyama without scale) and further
// iterations change nothing. The closed form is exact, needs no initial guess
// and has no convergence or iteration-limit failure modes, so we use it.
// The result composes both: T = T_step2 * Translation(t').

#include <l2s/registrar.hpp>

#include <l2s/error.hpp>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <sstream>

namespace l2s {
namespace {

/// A reason why a labelled point set cannot fix a rotation, or "".
std::string degeneracy(const HoleCenters& pts, const char* which, const Registrar::Params& params) {
  for (const auto& p : pts)
    if (!p.allFinite()) return std::string(which) + " centres contain NaN or infinity";
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= 4.0;
  Eigen::Matrix<double, 3, 4> centred;
  for (int i = 0; i < 4; ++i) centred.col(i) = pts[i] - mean;
  const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix<double, 3, 4>>(centred).singularValues();
  // Singular values relate to the rms extent: sigma_1 = 2 * rms along the main axis.
  std::ostringstream reason;
  if (sv(0) / 2.0 < params.min_extent) {
    reason << which << " centres coincide (extent " << sv(0) / 2.0 << " m)";
    return reason.str();
  }
  if (sv(1) / sv(0) < params.min_planarity) {
    reason << which << " centres are collinear (singular value ratio " << sv(1) / sv(0) << ")";
    return reason.str();
  }
  return {};
}

}  // namespace

void Registrar::Params::validate() const {
  if (!(min_extent > 0.0)) throw ParamError("min_extent", "must be > 0");
  if (!(min_planarity > 0.0 && min_planarity < 1.0))
    throw ParamError("min_planarity", "must be in (0, 1)");
}

Registrar::Registrar(Params params) : params_(params) { params_.validate(); }

Registrar::Result Registrar::estimate(const HoleCenters& lidar, const HoleCenters& camera) const {
  Result result;
  for (const auto* which : {"lidar", "camera"}) {
    result.reason = degeneracy(which[0] == 'l' ? lidar : camera, which, params_);
    if (!result.reason.empty()) return result;
  }

  // Step 1: A t = b with A = [I; I; I; I] (12 x 3), b = stacked p_l - p_c.
  Eigen::Matrix<double, 12, 3> A;
  Eigen::Matrix<double, 12, 1> b;
  for (int i = 0; i < 4; ++i) {
    A.block<3, 3>(3 * i, 0).setIdentity();
    b.segment<3>(3 * i) = lidar[i] - camera[i];
  }
  result.translation_only = A.colPivHouseholderQr().solve(b);

  // Step 2: rigid fit of the lidar points to the translated camera points.
  Eigen::Vector3d mean_c = Eigen::Vector3d::Zero(), mean_l = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, 4> moved;
  for (int i = 0; i < 4; ++i) {
    moved[i] = camera[i] + result.translation_only;
    mean_c += moved[i] / 4.0;
    mean_l += lidar[i] / 4.0;
  }
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i) H += (moved[i] - mean_c) * (lidar[i] - mean_l).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // Four coplanar points fix a rotation, but the SVD alone may return a
  // reflection; flipping the weakest axis restores a proper rotation.
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
  const Eigen::Matrix3d R = svd.matrixV() * D * svd.matrixU().transpose();
  Eigen::Isometry3d T_step2 = Eigen::Isometry3d::Identity();
  T_step2.linear() = R;
  T_step2.translation() = mean_l - R * mean_c;
  result.T_lidar_camera = T_step2 * Eigen::Translation3d(result.translation_only);
  if (!result.T_lidar_camera.matrix().allFinite()) {
    result.reason = "registration produced a non-finite transform";
    return result;
  }

  double sum_sq = 0.0;
  for (int i = 0; i < 4; ++i) {
    result.residuals[i] = (lidar[i] - result.T_lidar_camera * camera[i]).norm();
    sum_sq += result.residuals[i] * result.residuals[i];
  }
  result.rms = std::sqrt(sum_sq / 4.0);
  result.found = true;
  return result;
}

}  // namespace l2s
