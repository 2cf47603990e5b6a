// Sub-pixel board pose refinement from the hole silhouettes in both images.
// Why: a plane fitted to SGM points (paper Sec. III-B) is tilted by ~1 deg and
// offset by mm, which the registration turns into cm; hole rims in the images
// are sharp to a fraction of a pixel. Model-based edge alignment in the spirit
// of RAPiD-style trackers (Harris 1992; Drummond & Cipolla 2002):
//  - each hole is a cylinder through a slab of known thickness; its visible
//    aperture in a view is the intersection of the projections of the front
//    (z = 0) and back (z = -thickness) rim circles, so a rim sample counts only
//    when the line of sight through it passes inside the other rim;
//  - every counted sample searches along its projected normal for the
//    sub-pixel maximum of the directional gradient (bicubic sampling,
//    parabolic peak fit);
//  - Gauss-Newton on a left se(3) increment of T_camera_board minimises the
//    signed normal distances with Huber weights; search and fit alternate.
// Using the right image too gives each rim a disparity, i.e. the depth and
// tilt that a single view hardly observes.

#include <l2s/board_pose_refiner.hpp>

#include <l2s/error.hpp>

#include "camera/cv_image.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace l2s {
namespace {

/// Directional gradients of a crop of a gray image, in gray levels per pixel.
struct Gradient {
  cv::Mat gx, gy;  // CV_32F
  int x0 = 0, y0 = 0;

  /// Gradient at full-image coordinates (Catmull-Rom bicubic); false outside
  /// the crop. Bilinear interpolation would make the profile along a search
  /// line piecewise linear with kinks at the pixel grid, and the parabolic
  /// peak fit would lock towards them: a bias of ~0.02 px that differs
  /// between the views, i.e. ~1 mm of depth per hole at 3.5 m.
  bool at(double x, double y, Eigen::Vector2d& g) const {
    const double fx = x - x0, fy = y - y0;
    const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
    if (ix < 1 || iy < 1 || ix + 2 >= gx.cols || iy + 2 >= gx.rows) return false;
    const auto weights = [](double t, double w[4]) {
      const double t2 = t * t, t3 = t2 * t;
      w[0] = 0.5 * (-t3 + 2 * t2 - t);
      w[1] = 0.5 * (3 * t3 - 5 * t2 + 2);
      w[2] = 0.5 * (-3 * t3 + 4 * t2 + t);
      w[3] = 0.5 * (t3 - t2);
    };
    double wx[4], wy[4];
    weights(fx - ix, wx);
    weights(fy - iy, wy);
    const auto interp = [&](const cv::Mat& m) {
      double sum = 0.0;
      for (int j = 0; j < 4; ++j) {
        const float* r = m.ptr<float>(iy - 1 + j) + ix - 1;
        sum += wy[j] * (wx[0] * r[0] + wx[1] * r[1] + wx[2] * r[2] + wx[3] * r[3]);
      }
      return sum;
    };
    g = {interp(gx), interp(gy)};
    return true;
  }
};

Gradient gradient_of(const cv::Mat& gray, const cv::Rect& box) {
  Gradient grad;
  const cv::Rect crop = box & cv::Rect(0, 0, gray.cols, gray.rows);
  grad.x0 = crop.x;
  grad.y0 = crop.y;
  if (crop.area() <= 0) return grad;
  // 3x3 Sobel / 8 is the central difference smoothed across: gray levels / px.
  cv::Sobel(gray(crop), grad.gx, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(gray(crop), grad.gy, CV_32F, 0, 1, 3, 1.0 / 8.0);
  return grad;
}

/// One rectified camera: projection matrix P (left optical frame in) and centre.
struct View {
  Eigen::Matrix<double, 3, 4> P;
  Eigen::Vector3d center;  // [m] in the left optical frame
  int width = 0, height = 0;
  Gradient grad;

  bool project(const Eigen::Vector3d& p, Eigen::Vector2d& u, Eigen::Matrix<double, 2, 3>* J) const {
    const Eigen::Vector3d h = P * p.homogeneous();
    if (!(h.z() > 1e-6)) return false;
    u = h.head<2>() / h.z();
    if (J) *J = (P.topLeftCorner<2, 3>() - u * P.block<1, 3>(2, 0)) / h.z();
    return true;
  }
};

/// A rim point matched to an image edge in one view.
struct Sample {
  int view;
  Eigen::Vector3d X_board;   // [m] on a rim circle
  Eigen::Vector2d normal;    // unit, image normal of the projected rim
  Eigen::Vector2d observed;  // [px] edge position found on the search line
};

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

void BoardPoseRefiner::Params::validate() const {
  if (samples_per_rim < 16 || samples_per_rim > 2000) throw ParamError("samples_per_rim", "must be 16..2000");
  if (!(search_range_px >= 1.0 && search_range_px <= 30.0)) throw ParamError("search_range_px", "must be 1..30");
  if (!(final_search_range_px >= 1.0 && final_search_range_px <= search_range_px))
    throw ParamError("final_search_range_px", "must be 1..search_range_px");
  if (!(search_step_px >= 0.1 && search_step_px <= 2.0)) throw ParamError("search_step_px", "must be 0.1..2");
  if (!(min_rim_separation_px >= 0.0 && min_rim_separation_px <= 10.0))
    throw ParamError("min_rim_separation_px", "must be 0..10");
  if (!(min_edge_strength >= 0.0)) throw ParamError("min_edge_strength", "must be >= 0");
  if (!(huber_px > 0.0)) throw ParamError("huber_px", "must be > 0");
  if (max_iterations < 1) throw ParamError("max_iterations", "must be >= 1");
  if (gauss_newton_steps < 1) throw ParamError("gauss_newton_steps", "must be >= 1");
  if (!(image_margin_px >= 0.0)) throw ParamError("image_margin_px", "must be >= 0");
  if (!(converged_rotation > 0.0)) throw ParamError("converged_rotation", "must be > 0");
  if (!(converged_translation > 0.0)) throw ParamError("converged_translation", "must be > 0");
  if (!(converged_step_rms_fraction >= 0.0 && converged_step_rms_fraction <= 1.0))
    throw ParamError("converged_step_rms_fraction", "must be 0..1");
  if (!(min_edge_fraction >= 0.0 && min_edge_fraction <= 1.0)) throw ParamError("min_edge_fraction", "must be 0..1");
  if (min_samples < 7) throw ParamError("min_samples", "must be >= 7");
  if (!(max_rms_px > 0.0)) throw ParamError("max_rms_px", "must be > 0");
}

BoardPoseRefiner::BoardPoseRefiner(Params params) : params_(params) { params_.validate(); }

BoardPoseRefiner::Result BoardPoseRefiner::refine(const Image& left, const Image& right,
                                                  const StereoCamera& camera, const Target& target,
                                                  const Eigen::Isometry3d& T_camera_board) const {
  target.validate();
  detail::check_stereo_images(left, right, camera);
  const cv::Mat gray_left = detail::gray_mat(left, "left");
  const cv::Mat gray_right = detail::gray_mat(right, "right");
  Result result;
  result.T_camera_board = T_camera_board;
  if (!T_camera_board.matrix().allFinite()) {
    result.reason = "initial pose is not finite";
    return result;
  }

  const double r = target.hole_radius, thickness = target.board_thickness;
  const auto holes = target.hole_centers();
  const int n = params_.samples_per_rim;
  std::vector<Eigen::Vector3d> rim_points;  // board frame, [hole][rim][theta]
  std::vector<Eigen::Vector3d> rim_tangents;
  std::vector<int> rim_hole;
  for (int h = 0; h < 4; ++h)
    for (const double z : {0.0, -thickness})
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * M_PI * (k + 0.5) / n;
        rim_points.emplace_back(holes[h].x() + r * std::cos(a), holes[h].y() + r * std::sin(a), z);
        rim_tangents.emplace_back(-std::sin(a), std::cos(a), 0.0);
        rim_hole.push_back(h);
      }

  // Views, each with the gradient of the board's neighbourhood only.
  std::vector<View> views;
  const double baseline = camera.baseline();
  views.push_back({camera.left.projection_matrix, Eigen::Vector3d::Zero(), left.width, left.height, {}});
  if (params_.use_right_image)
    views.push_back({camera.right.projection_matrix, Eigen::Vector3d(baseline, 0, 0), right.width,
                     right.height, {}});
  for (std::size_t v = 0; v < views.size(); ++v) {
    double x_min = 1e18, y_min = 1e18, x_max = -1e18, y_max = -1e18;
    for (const auto& X : rim_points) {
      Eigen::Vector2d u;
      if (!views[v].project(T_camera_board * X, u, nullptr)) continue;
      x_min = std::min(x_min, u.x()); x_max = std::max(x_max, u.x());
      y_min = std::min(y_min, u.y()); y_max = std::max(y_max, u.y());
    }
    if (x_min > x_max) {
      result.reason = "the board is behind a camera";
      return result;
    }
    const double pad = 4.0 * params_.search_range_px + 20.0;  // room for the pose to move
    const cv::Rect box(cv::Point(static_cast<int>(x_min - pad), static_cast<int>(y_min - pad)),
                       cv::Point(static_cast<int>(x_max + pad), static_cast<int>(y_max + pad)));
    views[v].grad = gradient_of(v == 0 ? gray_left : gray_right, box);
  }

  Eigen::Isometry3d T = T_camera_board;
  std::vector<Sample> samples;
  std::vector<double> profile;
  bool settled = false;
  double previous_step_px = std::numeric_limits<double>::infinity();
  int searched_at_selection = 0;
  // Which (view, rim point) samples are used. Visibility and the separation
  // test are decided afresh while the search range shrinks, then frozen:
  // samples toggling at those thresholds would otherwise keep the pose
  // jittering by a few 1e-5 and never let the rounds settle. Once frozen, a
  // sample that loses its edge (too weak, window clipped) is dropped for good,
  // so the set only shrinks and cannot toggle either.
  std::vector<char> chosen(views.size() * rim_points.size(), 0);
  bool lock_selection = false;
  for (int round = 0; round < params_.max_iterations && !settled; ++round) {
    result.iterations = round + 1;
    const double range = std::max(params_.final_search_range_px, params_.search_range_px / (1 << std::min(round, 20)));
    const int steps = static_cast<int>(std::floor(range / params_.search_step_px));
    profile.assign(2 * steps + 1, 0.0);
    const bool locked = lock_selection;
    lock_selection = range <= params_.final_search_range_px;
    // Search: visible silhouette samples and their edges.
    samples.clear();
    int searched = 0;  // samples whose search line was inside the image, edge or not
    const Eigen::Isometry3d T_board_camera = T.inverse();
    for (std::size_t v = 0; v < views.size(); ++v) {
      const View& view = views[v];
      const Eigen::Vector3d eye = T_board_camera * view.center;  // camera centre, board frame
      if (!(eye.z() > 0.0)) continue;  // looking at the back face
      for (std::size_t k = 0; k < rim_points.size(); ++k) {
        const Eigen::Vector3d& X = rim_points[k];
        char& use = chosen[v * rim_points.size() + k];
        if (locked && !use) continue;
        use = 0;
        if (!locked) {
          // The line of sight through X must pass inside the other rim circle.
          const double other_z = X.z() == 0.0 ? -thickness : 0.0;
          const double s = (other_z - eye.z()) / (X.z() - eye.z());
          const Eigen::Vector3d Q = eye + s * (X - eye);
          if ((Q.head<2>() - holes[rim_hole[k]]).norm() > r) continue;
        }
        Eigen::Vector2d u;
        Eigen::Matrix<double, 2, 3> J;
        const Eigen::Vector3d p = T * X;
        if (!view.project(p, u, &J)) continue;
        const double m = params_.image_margin_px + range;
        if (u.x() < m || u.y() < m || u.x() > view.width - 1 - m || u.y() > view.height - 1 - m) continue;
        const Eigen::Vector2d tangent = J * (T.linear() * rim_tangents[k]);
        if (tangent.norm() < 1e-9) continue;
        const Eigen::Vector2d normal(-tangent.y() / tangent.norm(), tangent.x() / tangent.norm());
        // Search window, profile indices lo..hi (offset -steps..steps).
        int lo = 0, hi = 2 * steps;
        if (X.z() != 0.0) {
          // A back-rim silhouette has the hole wall beside it, bounded by the
          // front rim's edge (face | wall | back rim | background). When that
          // band is narrow both edges merge into one gradient peak whose
          // position is biased, differently in each view.
          Eigen::Vector2d u_front;
          if (!view.project(T * Eigen::Vector3d(X.x(), X.y(), 0.0), u_front, nullptr)) continue;
          const double separation = normal.dot(u_front - u);  // [px] signed, along the normal
          if (!locked && std::abs(separation) < params_.min_rim_separation_px) continue;
          // The face-to-wall edge is often the stronger one (a wall in shadow
          // is as dark as what is seen through the hole), so the search must
          // not reach it: stop half a pixel short of half-way to the front rim
          // on that side, whatever the step (the Sobel response of that edge
          // is ~1.5 px wide; a window ending on its flank finds a biased peak).
          const int reach = std::max(
              1, static_cast<int>(std::floor((0.5 * std::abs(separation) - 0.5) / params_.search_step_px)));
          if (separation > 0.0)
            hi = std::min(hi, steps + reach);
          else
            lo = std::max(lo, steps - reach);
        }
        bool inside = true;
        for (int i = lo; i <= hi && inside; ++i) {
          Eigen::Vector2d g;
          inside = view.grad.at(u.x() + (i - steps) * params_.search_step_px * normal.x(),
                                u.y() + (i - steps) * params_.search_step_px * normal.y(), g);
          profile[i] = std::abs(g.dot(normal));
        }
        if (!inside) continue;
        ++searched;
        int best = lo + 1;
        for (int i = lo + 1; i < hi; ++i)
          if (profile[i] > profile[best]) best = i;
        if (profile[best] < params_.min_edge_strength) continue;
        // Still rising at a clipped end: the peak is the front rim's, beyond.
        if ((lo > 0 && profile[lo] > profile[best]) || (hi < 2 * steps && profile[hi] > profile[best])) continue;
        const double a = profile[best - 1], b = profile[best], c = profile[best + 1];
        const double denom = a - 2.0 * b + c;
        const double offset = denom < 0.0 ? 0.5 * (a - c) / denom : 0.0;
        const double along = (best - steps + offset) * params_.search_step_px;
        use = 1;
        samples.push_back({static_cast<int>(v), X, normal, u + along * normal});
      }
    }
    result.samples = static_cast<int>(samples.size());
    // Share of the rim that shows an edge. Once the selection is locked, the
    // samples that found no edge are no longer searched, so the base stays the
    // count of the round that chose them.
    if (!locked) searched_at_selection = searched;
    result.edge_fraction =
        searched_at_selection > 0 ? static_cast<double>(result.samples) / searched_at_selection : 0.0;
    if (result.samples < params_.min_samples) {
      std::ostringstream reason;
      reason << "only " << result.samples << " rim edge samples found (need " << params_.min_samples << ")";
      result.reason = reason.str();
      result.T_camera_board = T;
      return result;
    }

    // Fit: Gauss-Newton with the found edges held fixed.
    const Eigen::Isometry3d T_round_start = T;
    Eigen::Vector3d round_rotation = Eigen::Vector3d::Zero(), round_translation = Eigen::Vector3d::Zero();
    for (int step = 0; step < params_.gauss_newton_steps; ++step) {
      Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
      Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
      double sum_sq = 0.0, sum_w = 0.0;
      for (const Sample& sample : samples) {
        const Eigen::Vector3d p = T * sample.X_board;
        Eigen::Vector2d u;
        Eigen::Matrix<double, 2, 3> J;
        if (!views[sample.view].project(p, u, &J)) continue;
        const double residual = sample.normal.dot(u - sample.observed);
        Eigen::Matrix<double, 3, 6> dp;  // d(exp(delta) p) / d(v, omega) at 0
        dp << Eigen::Matrix3d::Identity(), -skew(p);
        const Eigen::Matrix<double, 1, 6> row = sample.normal.transpose() * J * dp;
        const double w = std::abs(residual) <= params_.huber_px ? 1.0 : params_.huber_px / std::abs(residual);
        H += w * row.transpose() * row;
        g += w * row.transpose() * residual;
        sum_sq += residual * residual;
        sum_w += 1.0;
      }
      result.rms_px = std::sqrt(sum_sq / std::max(sum_w, 1.0));
      H.diagonal() *= 1.0 + 1e-9;  // keeps LDLT well defined if an axis is barely observed
      const Eigen::Matrix<double, 6, 1> delta = -H.ldlt().solve(g);
      if (!delta.allFinite()) {
        result.reason = "pose update is not finite (degenerate rim samples)";
        result.T_camera_board = T;
        return result;
      }
      const Eigen::Vector3d v = delta.head<3>(), w = delta.tail<3>();
      const Eigen::Matrix3d R_delta =
          w.norm() > 0.0 ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                         : Eigen::Matrix3d::Identity();
      Eigen::Isometry3d next = Eigen::Isometry3d::Identity();
      next.linear() = R_delta * T.linear();
      next.translation() = R_delta * T.translation() + v;
      T = next;
      round_rotation += w;
      round_translation += v;
    }
    settled = round_rotation.norm() < params_.converged_rotation &&
              round_translation.norm() < params_.converged_translation;

    // The se(3) test above is strict: the edge positions are re-sampled each
    // round, so their sub-pixel interpolation bias moves with the pose and the
    // rounds often settle by a slowly damped oscillation (a few 1e-4 rad about
    // the camera, i.e. ~0.01 px on the rims, at rms ~0.08 px) that the round
    // limit cuts off. What matters is how far the round moved the rims in the
    // images: once that step is shrinking and a small fraction of the edge
    // noise (rms), further rounds cannot change the pose beyond its own
    // uncertainty. Only with the final search range (selection locked), and
    // only when most searched rim samples found a strong edge: on an image
    // without the board, wall texture yields some edges that a pose can
    // settle on too, but not along most of the rims.
    double step_px = 0.0;  // largest image motion of a used sample in this round
    for (const Sample& sample : samples) {
      Eigen::Vector2d before, after;
      if (views[sample.view].project(T_round_start * sample.X_board, before, nullptr) &&
          views[sample.view].project(T * sample.X_board, after, nullptr))
        step_px = std::max(step_px, (after - before).norm());
    }
    if (!settled && locked && step_px < previous_step_px &&
        step_px <= params_.converged_step_rms_fraction * result.rms_px &&
        result.edge_fraction >= params_.min_edge_fraction)
      settled = true;
    previous_step_px = step_px;
    result.last_step_px = step_px;
  }

  result.T_camera_board = T;
  for (int h = 0; h < 4; ++h) result.centers[h] = T * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0);
  std::ostringstream reason;
  if (!settled) {
    reason << "not converged after " << result.iterations << " rounds (last step " << result.last_step_px
           << " px, rms " << result.rms_px << " px, " << std::lround(100.0 * result.edge_fraction)
           << "% of rim samples on an edge)";
  } else if (result.rms_px > params_.max_rms_px) {
    reason << "edge rms " << result.rms_px << " px exceeds " << params_.max_rms_px << " px";
  }
  result.reason = reason.str();
  result.converged = result.reason.empty();
  return result;
}

}  // namespace l2s
