// The search-and-fit rounds of the board pose refinement (see
// rim_alignment.hpp; the method as a whole is described in
// board_pose_refiner.cpp): Gauss-Newton on a left se(3) increment of
// T_camera_board with Huber weights on the rims, and, for the outline,
// Tukey weights and its own nuisance.

#include "camera/rim_alignment.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

namespace l2s::detail {
namespace {

using Params = BoardPoseRefiner::Params;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// One left se(3) increment of T: rotation w [rad] about the camera origin, then translation v [m].
Eigen::Isometry3d apply_increment(const Eigen::Isometry3d& T, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  const Eigen::Matrix3d R_delta =
      w.norm() > 0.0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                     : Eigen::Matrix3d::Identity();
  Eigen::Isometry3d next = Eigen::Isometry3d::Identity();
  next.linear() = R_delta * T.linear();
  next.translation() = R_delta * T.translation() + v;
  return next;
}

/// Where a sample's edge is expected in its view at pose T.
bool expected_at(const Sample& sample, const std::vector<View>& views, const Eigen::Isometry3d& T,
                 const OutlineNuisance& nuisance, Eigen::Vector2d& u, Eigen::Matrix<double, 2, 3>* J) {
  const Eigen::Vector3d X =
      sample.outline ? Eigen::Vector3d(sample.X_board + sample.outward.cwiseProduct(
                                                            Eigen::Vector3d(nuisance.dilation.x(), nuisance.dilation.y(), 0.0)))
                     : sample.X_board;
  if (!views[sample.view].project(T * X, u, J)) return false;
  if (sample.outline && sample.view == 1) u.x() += nuisance.disparity_px;
  return true;
}

/// [px] Outline samples farther than this from their edge weigh nothing
/// (Tukey's biweight below): unlike the rims, the outline is often partly
/// hidden (a box or a post in front of a corner, the board's stand) or runs
/// along a background as bright as the board, and there the search finds
/// some other edge. The stage starts from the rims' converged pose, so a
/// redescending weight is safe.
constexpr double kOutlineCutoffPx = 1.0;

double outline_weight(double residual) {
  const double t = residual / kOutlineCutoffPx;
  return std::abs(t) < 1.0 ? (1.0 - t * t) * (1.0 - t * t) : 0.0;
}

using Increment = Eigen::Matrix<double, 9, 1>;  // v, omega, outline disparity, outline dilation (x, y)

/// The Gauss-Newton increment for the signed normal distances of the
/// samples at pose T, Huber-weighted; `rms_px` gets their rms. The outline's
/// nuisance stays fixed (increment 0) unless `free_nuisance`.
Increment gauss_newton_delta(const std::vector<Sample>& samples, const std::vector<View>& views,
                             const Eigen::Isometry3d& T, const OutlineNuisance& nuisance, bool free_nuisance,
                             double huber_px, double& rms_px) {
  Eigen::Matrix<double, 9, 9> H = Eigen::Matrix<double, 9, 9>::Zero();
  Increment g = Increment::Zero();
  double sum_sq = 0.0, sum_w = 0.0;
  for (const Sample& sample : samples) {
    Eigen::Vector2d u;
    Eigen::Matrix<double, 2, 3> J;
    if (!expected_at(sample, views, T, nuisance, u, &J)) continue;
    const Eigen::Vector3d p = T * sample.X_board;
    const double residual = sample.normal.dot(u - sample.observed);
    Eigen::Matrix<double, 3, 6> dp;  // d(exp(delta) p) / d(v, omega) at 0
    dp << Eigen::Matrix3d::Identity(), -skew(p);
    Eigen::Matrix<double, 1, 9> row = Eigen::Matrix<double, 1, 9>::Zero();
    row.head<6>() = sample.normal.transpose() * J * dp;
    if (sample.outline) {
      row(6) = sample.view == 1 ? sample.normal.x() : 0.0;
      row(7) = sample.normal.dot(J * (T.linear().col(0) * sample.outward.x()));
      row(8) = sample.normal.dot(J * (T.linear().col(1) * sample.outward.y()));
    }
    const double w = sample.outline ? outline_weight(residual)
                                    : sample.weight * (std::abs(residual) <= huber_px ? 1.0 : huber_px / std::abs(residual));
    H += w * row.transpose() * row;
    g += w * row.transpose() * residual;
    if (!sample.rim || (sample.outline && w == 0.0)) continue;
    sum_sq += residual * residual;
    sum_w += 1.0;
  }
  rms_px = std::sqrt(sum_sq / std::max(sum_w, 1.0));
  for (int k = 6; k < 9; ++k)
    if (!free_nuisance || H(k, k) <= 0.0) {
      H.row(k).setZero();
      H.col(k).setZero();
      H(k, k) = 1.0;
      g(k) = 0.0;
    }
  H.diagonal() *= 1.0 + 1e-9;  // keeps LDLT well defined if an axis is barely observed
  return -H.ldlt().solve(g);
}

/// The outline's dilation as the median over its samples of what each one's
/// edge alone says (the others at zero): the start of the fit, so that sides
/// cut a centimetre off their nominal place are not taken for outliers
/// (kOutlineCutoffPx) before the dilation could reach them.
OutlineNuisance median_outline_nuisance(const std::vector<Sample>& samples, const std::vector<View>& views,
                                        const Eigen::Isometry3d& T) {
  std::array<std::vector<double>, 2> says;  // [m] per axis
  for (const Sample& sample : samples) {
    Eigen::Vector2d u;
    Eigen::Matrix<double, 2, 3> J;
    if (!sample.outline || !expected_at(sample, views, T, {}, u, &J)) continue;
    const double residual = sample.normal.dot(u - sample.observed);
    for (int axis = 0; axis < 2; ++axis) {
      const double slope = sample.normal.dot(J * (T.linear().col(axis) * sample.outward[axis]));
      if (std::abs(slope) > 1e-6) says[axis].push_back(-residual / slope);
    }
  }
  OutlineNuisance nuisance;
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double>& v = says[axis];
    if (v.empty()) continue;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    nuisance.dilation[axis] = v[v.size() / 2];
  }
  return nuisance;
}

/// How far one round moved the pose.
struct RoundMotion {
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();     // [rad] sum of the steps' omega
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // [m] sum of the steps' v
};

/// The fit half of a round: Gauss-Newton steps with the found edges held
/// fixed. Moves T (and the outline's nuisance when `free_nuisance`); false
/// when an update is not finite (T is then the pose before that step).
bool fit_pose(const std::vector<Sample>& samples, const std::vector<View>& views, const Params& params,
              Eigen::Isometry3d& T, OutlineNuisance& nuisance, bool free_nuisance, RoundMotion& motion,
              double& rms_px) {
  for (int step = 0; step < params.gauss_newton_steps; ++step) {
    const Increment delta = gauss_newton_delta(samples, views, T, nuisance, free_nuisance, params.huber_px, rms_px);
    if (!delta.allFinite()) return false;
    const Eigen::Vector3d v = delta.head<3>(), w = delta.segment<3>(3);
    T = apply_increment(T, v, w);
    nuisance.disparity_px += delta(6);
    nuisance.dilation += delta.tail<2>();
    motion.rotation += w;
    motion.translation += v;
  }
  return true;
}

/// [px] largest image motion of a used sample between two poses.
double largest_image_step(const std::vector<Sample>& samples, const std::vector<View>& views,
                          const Eigen::Isometry3d& T_before, const Eigen::Isometry3d& T_after) {
  double step_px = 0.0;
  for (const Sample& sample : samples) {
    Eigen::Vector2d before, after;
    if (views[sample.view].project(T_before * sample.X_board, before, nullptr) &&
        views[sample.view].project(T_after * sample.X_board, after, nullptr))
      step_px = std::max(step_px, (after - before).norm());
  }
  return step_px;
}

/// Why the refinement is not trusted, empty when it is.
std::string failure_reason(const BoardPoseRefiner::Result& result, bool settled, const Params& params) {
  std::ostringstream reason;
  if (!settled) {
    reason << "not converged after " << result.iterations << " rounds (last step " << result.last_step_px
           << " px, rms " << result.rms_px << " px, " << std::lround(100.0 * result.edge_fraction)
           << "% of rim samples on an edge)";
  } else if (result.rms_px > params.max_rms_px) {
    reason << "edge rms " << result.rms_px << " px exceeds " << params.max_rms_px << " px";
  }
  return reason.str();
}

std::string too_few_samples(int samples, int min_samples) {
  std::ostringstream reason;
  reason << "only " << samples << " rim edge samples found (need " << min_samples << ")";
  return reason.str();
}

/// The second convergence test. The se(3) test (converged_rotation,
/// converged_translation) is strict: the edge positions are re-sampled each
/// round, so their sub-pixel interpolation bias moves with the pose and the
/// rounds often settle by a slowly damped oscillation (a few 1e-4 rad about
/// the camera, i.e. ~0.01 px on the rims, at rms ~0.08 px) that the round
/// limit cuts off. What matters is how far the round moved the rims in the
/// images: once that step is shrinking and a small fraction of the edge
/// noise (rms), further rounds cannot change the pose beyond its own
/// uncertainty. Only with the final search range (selection locked), and
/// only when most searched rim samples found a strong edge: on an image
/// without the board, wall texture yields some edges that a pose can
/// settle on too, but not along most of the rims.
bool settled_in_image(double step_px, double previous_step_px, bool locked, const BoardPoseRefiner::Result& result,
                      const Params& params) {
  return locked && step_px < previous_step_px && step_px <= params.converged_step_rms_fraction * result.rms_px &&
         result.edge_fraction >= params.min_edge_fraction;
}

}  // namespace

SampleFit fit_of(const std::vector<Sample>& samples, const std::vector<View>& views, const Eigen::Isometry3d& T,
                 const OutlineNuisance& nuisance, bool outline) {
  double sum_sq = 0.0;
  int count = 0, all = 0;
  for (const Sample& sample : samples) {
    Eigen::Vector2d u;
    if (!sample.rim || sample.outline != outline || !expected_at(sample, views, T, nuisance, u, nullptr))
      continue;
    ++all;
    const double residual = sample.normal.dot(u - sample.observed);
    if (outline && !(std::abs(residual) < kOutlineCutoffPx)) continue;
    sum_sq += residual * residual;
    ++count;
  }
  SampleFit fit;
  if (count > 0) fit.rms_px = std::sqrt(sum_sq / count);
  fit.inlier_share = all > 0 ? static_cast<double>(count) / all : 0.0;
  fit.inliers = count;
  return fit;
}

void Alignment::run(const Eigen::Isometry3d& T_camera_board, BoardPoseRefiner::Result& result) {
  Eigen::Isometry3d T = T_camera_board;
  for (int round = 0; round < params_.max_iterations && !settled_; ++round)
    if (!run_round(round, T, result)) {
      result.T_camera_board = T;
      return;
    }
  result.T_camera_board = T;
  for (int h = 0; h < 4; ++h)
    result.centers[h] = T * Eigen::Vector3d(rims_.centers[h].x(), rims_.centers[h].y(), 0.0);
  result.reason = failure_reason(result, settled_, params_);
}

bool Alignment::run_round(int round, Eigen::Isometry3d& T, BoardPoseRefiner::Result& result) {
  result.iterations = round + 1;
  const double range = std::max(params_.final_search_range_px, params_.search_range_px / (1 << std::min(round, 20)));
  const bool locked = lock_selection_;
  lock_selection_ = range <= params_.final_search_range_px;
  const int searched = edges_.search(T, range, locked, samples_);
  result.samples = static_cast<int>(samples_.size());
  // Share of the rim that shows an edge. Once the selection is locked, the
  // samples that found no edge are no longer searched, so the base stays the
  // count of the round that chose them.
  if (!locked) searched_at_selection_ = searched;
  result.edge_fraction =
      searched_at_selection_ > 0 ? static_cast<double>(result.samples) / searched_at_selection_ : 0.0;
  if (result.samples < params_.min_samples) {
    result.reason = too_few_samples(result.samples, params_.min_samples);
    return false;
  }

  if (free_nuisance_ && round == 0) nuisance_ = median_outline_nuisance(samples_, views_, T);
  samples_.insert(samples_.end(), anchors_.begin(), anchors_.end());
  const Eigen::Isometry3d T_round_start = T;
  RoundMotion motion;
  if (!fit_pose(samples_, views_, params_, T, nuisance_, free_nuisance_, motion, result.rms_px)) {
    result.reason = "pose update is not finite (degenerate rim samples)";
    return false;
  }
  settled_ = motion.rotation.norm() < params_.converged_rotation &&
             motion.translation.norm() < params_.converged_translation;
  const double step_px = largest_image_step(samples_, views_, T_round_start, T);
  if (!settled_ && settled_in_image(step_px, previous_step_px_, locked, result, params_)) settled_ = true;
  previous_step_px_ = step_px;
  result.last_step_px = step_px;
  return true;
}

}  // namespace l2s::detail
