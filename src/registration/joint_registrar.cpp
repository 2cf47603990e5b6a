// One rigid fit over the labelled centre pairs of every board pose (issue 9).
// One pose: Registrar, the paper's two steps (Sec. III-D), unchanged. Several:
// the same two steps over all 4 P pairs; the translation-only step followed
// by the rigid fit composes to the closed-form least-squares rigid fit of all
// pairs (Kabsch without scale), which is what is computed.
// Robustness: a pose whose centres are wrong (a mislabelled pattern, a
// detection on the wrong plane that clustered anyway) pulls a joint fit
// towards it, so it is judged by the fit of the other poses: its residual
// there against theirs. The worst such pose is rejected while it stands out
// and at least `min_poses_to_reject` poses remain to judge by.

#include <l2s/joint_registrar.hpp>

#include <l2s/error.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace l2s {
namespace {

struct Fit {
  bool found = false;
  std::string reason;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  Registrar::Result single;
};

/// Closed-form least-squares rigid fit target ~ R source + t of the finite pairs.
bool rigid_fit(const std::vector<PosePair>& poses, const std::vector<int>& use, Eigen::Isometry3d* T) {
  std::vector<Eigen::Vector3d> t, s;
  for (int p : use)
    for (int h = 0; h < 4; ++h)
      if (poses[p].target[h].allFinite() && poses[p].source[h].allFinite())
        t.push_back(poses[p].target[h]), s.push_back(poses[p].source[h]);
  if (t.size() < 3) return false;
  Eigen::Vector3d mean_t = Eigen::Vector3d::Zero(), mean_s = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < t.size(); ++i) mean_t += t[i] / t.size(), mean_s += s[i] / s.size();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < t.size(); ++i) H += (s[i] - mean_s) * (t[i] - mean_t).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  if (!(svd.singularValues()[1] > 1e-9 * svd.singularValues()[0])) return false;  // collinear
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
  T->setIdentity();
  T->linear() = svd.matrixV() * D * svd.matrixU().transpose();
  T->translation() = mean_t - T->linear() * mean_s;
  return T->matrix().allFinite();
}

Fit fit(const std::vector<PosePair>& poses, const std::vector<int>& use, const Registrar& registrar) {
  Fit out;
  if (use.size() == 1) {
    out.single = registrar.estimate(poses[use[0]].target, poses[use[0]].source);
    out.found = out.single.found;
    out.reason = out.single.reason;
    out.T = out.single.T_lidar_camera;
    return out;
  }
  // Each pose must be a usable pattern on its own (no NaN, no collapse).
  for (int p : use) {
    const Registrar::Result alone = registrar.estimate(poses[p].target, poses[p].source);
    if (!alone.found) {
      out.reason = "pose " + std::to_string(p) + ": " + alone.reason;
      return out;
    }
  }
  out.found = rigid_fit(poses, use, &out.T);
  if (!out.found) out.reason = "the poses' centres do not fix a rigid transform";
  return out;
}

double rms_of(const std::vector<PosePair>& poses, const std::vector<int>& which, const Eigen::Isometry3d& T) {
  double sum = 0.0;
  int n = 0;
  for (int p : which)
    for (int h = 0; h < 4; ++h) sum += (poses[p].target[h] - T * poses[p].source[h]).squaredNorm(), ++n;
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

FitUncertainty uncertainty_of(const std::vector<PosePair>& poses, const std::vector<int>& use,
                              const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3d> target, source;
  for (int p : use)
    for (int h = 0; h < 4; ++h) target.push_back(poses[p].target[h]), source.push_back(poses[p].source[h]);
  return fit_uncertainty(target, source, T);
}

std::vector<int> without(const std::vector<int>& use, int p) {
  std::vector<int> out;
  for (int q : use)
    if (q != p) out.push_back(q);
  return out;
}

/// The jackknife over poses (Quenouille-Tukey): var = (P-1)/P sum (theta_-p
/// - mean)^2 per DoF, from the leave-one-pose-out shifts; needs P >= 3 (with
/// two, each half is one pose and the spread says little). Widens `u`.
void widen_by_jackknife(const std::vector<JointRegistrar::LeaveOneOut>& loo, int poses, FitUncertainty& u) {
  if (poses < 3 || !u.valid || static_cast<int>(loo.size()) != poses) return;
  for (const auto& l : loo)
    if (!l.found) return;
  const double t95 = student_t_95(poses - 1);
  for (int k = 0; k < 6; ++k) {
    double mean = 0.0, sum_sq = 0.0;
    for (const auto& l : loo) mean += l.shift[k] / poses;
    for (const auto& l : loo) sum_sq += (l.shift[k] - mean) * (l.shift[k] - mean);
    const double sigma = std::sqrt((poses - 1.0) / poses * sum_sq);
    u.sigma_between_poses[k] = sigma;
    u.bound_95[k] = std::max(u.bound_95[k], t95 * sigma);
    u.sigma[k] = std::max(u.sigma[k], sigma);
  }
}

/// The error a pose's detection shares across its centres, target frame:
/// the isotropic pose bias of `params` and the pose's own source_bias.
MotionCovariance pose_bias(const PosePair& pose, const Eigen::Matrix3d& R_target_source,
                           const JointRegistrar::Params& params) {
  MotionCovariance turn = MotionCovariance::Zero();
  turn.topLeftCorner<3, 3>() = R_target_source;
  turn.bottomRightCorner<3, 3>() = R_target_source;
  MotionCovariance bias = turn * pose.source_bias * turn.transpose();
  bias.topLeftCorner<3, 3>().diagonal().array() += params.pose_bias_translation * params.pose_bias_translation;
  bias.bottomRightCorner<3, 3>().diagonal().array() += params.pose_bias_rotation * params.pose_bias_rotation;
  return bias;
}

}  // namespace

void JointRegistrar::Params::validate() const {
  if (!(outlier_ratio > 1.0)) throw ParamError("outlier_ratio", "must be > 1");
  if (!(outlier_floor >= 0.0)) throw ParamError("outlier_floor", "must be >= 0");
  if (min_poses_to_reject < 3) throw ParamError("min_poses_to_reject", "must be >= 3");
  if (!(max_condition > 1.0)) throw ParamError("max_condition", "must be > 1");
  if (!(pose_bias_translation >= 0.0)) throw ParamError("pose_bias_translation", "must be >= 0 m");
  if (!(pose_bias_rotation >= 0.0)) throw ParamError("pose_bias_rotation", "must be >= 0 rad");
}

JointRegistrar::JointRegistrar(Params params, Registrar::Params registrar) : params_(params), registrar_(registrar) {
  params_.validate();
  registrar_.validate();
}

int JointRegistrar::Result::used_count() const { return static_cast<int>(std::count(used.begin(), used.end(), true)); }

JointRegistrar::Result JointRegistrar::estimate(const std::vector<PosePair>& poses) const {
  Result result;
  if (poses.empty()) {
    result.reason = "no board poses";
    return result;
  }
  const Registrar registrar(registrar_);
  std::vector<int> use(poses.size());
  for (std::size_t p = 0; p < poses.size(); ++p) use[p] = static_cast<int>(p);
  Fit current = fit(poses, use, registrar);
  if (!current.found) {
    result.reason = current.reason;
    return result;
  }
  // Reject the worst pose, judged by the fit of the others, while one stands out.
  while (static_cast<int>(use.size()) >= params_.min_poses_to_reject) {
    int worst = -1;
    double worst_ratio = 0.0, worst_rms = 0.0, expected_rms = 0.0;
    for (int p : use) {
      const std::vector<int> rest = without(use, p);
      const Fit other = fit(poses, rest, registrar);
      if (!other.found) continue;
      const double own = rms_of(poses, {p}, other.T);
      const double expected = prediction_rms(uncertainty_of(poses, rest, other.T), other.T,
                                             std::vector<Eigen::Vector3d>(poses[p].source.begin(), poses[p].source.end()));
      if (expected > 0.0 && own / expected > worst_ratio)
        worst = p, worst_ratio = own / expected, worst_rms = own, expected_rms = expected;
    }
    if (worst < 0 || worst_rms <= params_.outlier_floor || worst_ratio <= params_.outlier_ratio) break;
    const std::vector<int> rest = without(use, worst);
    const Fit refit = fit(poses, rest, registrar);
    if (!refit.found) break;
    std::ostringstream note;
    note.precision(3);
    note << "pose " << worst << " rejected: its centres miss the fit of the other poses by " << worst_rms * 1e3
         << " mm rms where " << expected_rms * 1e3 << " mm were expected";
    result.notes.push_back(note.str());
    use = rest;
    current = refit;
  }

  result.found = true;
  result.T_target_source = current.T;
  result.single = current.single;
  result.used.assign(poses.size(), false);
  for (int p : use) result.used[p] = true;
  for (const PosePair& pose : poses) {
    std::array<double, 4> r{};
    for (int h = 0; h < 4; ++h) r[h] = (pose.target[h] - current.T * pose.source[h]).norm();
    result.residuals.push_back(r);
    result.pose_rms.push_back(rms_of({pose}, {0}, current.T));
  }
  result.rms = rms_of(poses, use, current.T);

  result.uncertainty = uncertainty_of(poses, use, current.T);
  std::vector<std::vector<Eigen::Vector3d>> pose_sources;
  std::vector<MotionCovariance> pose_biases;
  for (int p : use) {
    pose_sources.emplace_back(poses[p].source.begin(), poses[p].source.end());
    pose_biases.push_back(pose_bias(poses[p], current.T.linear(), params_));
  }
  add_shared_group_error(result.uncertainty, current.T, pose_sources, pose_biases);
  if (result.uncertainty.valid && result.uncertainty.condition <= params_.max_condition)
    result.uncertainty.suggestion.clear();  // well conditioned: nothing to suggest

  if (use.size() >= 2) {
    const Eigen::Vector3d rpy = roll_pitch_yaw(current.T.rotation());
    for (int p : use) {
      LeaveOneOut loo;
      loo.pose = p;
      const Fit other = fit(poses, without(use, p), registrar);
      loo.found = other.found;
      if (other.found) {
        const PoseError e = pose_error(other.T, current.T);
        loo.translation = e.translation;
        loo.rotation = e.rotation;
        const Eigen::Vector3d dt = other.T.translation() - current.T.translation();
        const Eigen::Vector3d drpy = roll_pitch_yaw(other.T.rotation()) - rpy;
        for (int k = 0; k < 3; ++k) loo.shift[k] = dt[k], loo.shift[3 + k] = std::remainder(drpy[k], 2.0 * M_PI);
      }
      result.leave_one_out.push_back(loo);
    }
    widen_by_jackknife(result.leave_one_out, static_cast<int>(use.size()), result.uncertainty);
  }
  return result;
}

}  // namespace l2s
