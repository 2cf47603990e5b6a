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
//    signed normal distances with Huber weights; search and fit alternate;
//  - gray images first; colour ones (strongest channel per sample) when those
//    fail, for rims that differ from the face in hue more than in brightness.
// Using the right image too gives each rim a disparity, i.e. the depth and
// tilt that a single view hardly observes.

#include <l2s/board_pose_refiner.hpp>

#include <l2s/error.hpp>

#include "camera/cv_image.hpp"
#include "camera/noise_level.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace l2s {
namespace {

/// Directional gradients of a crop of an 8-bit image, in gray levels per
/// pixel: one pair per channel (one for gray, three for colour).
struct Gradient {
  std::vector<cv::Mat> gx, gy;  // CV_32F, per channel
  int x0 = 0, y0 = 0;

  /// The strongest channel's |gradient . normal| at full-image coordinates
  /// (Catmull-Rom bicubic); false outside the crop. Bilinear interpolation
  /// would make the profile along a search line piecewise linear with kinks
  /// at the pixel grid, and the parabolic peak fit would lock towards them:
  /// a bias of ~0.02 px that differs between the views, i.e. ~1 mm of depth
  /// per hole at 3.5 m.
  bool along(double x, double y, const Eigen::Vector2d& normal, double& value) const {
    if (gx.empty()) return false;
    const double fx = x - x0, fy = y - y0;
    const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
    if (ix < 1 || iy < 1 || ix + 2 >= gx[0].cols || iy + 2 >= gx[0].rows) return false;
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
    value = 0.0;
    for (std::size_t c = 0; c < gx.size(); ++c)
      value = std::max(value, std::abs(interp(gx[c]) * normal.x() + interp(gy[c]) * normal.y()));
    return true;
  }
};

Gradient gradient_of(const cv::Mat& image, const cv::Rect& box) {
  Gradient grad;
  const cv::Rect crop = box & cv::Rect(0, 0, image.cols, image.rows);
  grad.x0 = crop.x;
  grad.y0 = crop.y;
  if (crop.area() <= 0) return grad;
  std::vector<cv::Mat> channels;
  cv::split(image(crop), channels);
  for (const cv::Mat& channel : channels) {
    // 3x3 Sobel / 8 is the central difference smoothed across: gray levels / px.
    grad.gx.emplace_back();
    grad.gy.emplace_back();
    cv::Sobel(channel, grad.gx.back(), CV_32F, 1, 0, 3, 1.0 / 8.0);
    cv::Sobel(channel, grad.gy.back(), CV_32F, 0, 1, 3, 1.0 / 8.0);
  }
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
  Eigen::Vector3d X_board;   // [m] on a rim circle (or a known point: an anchor)
  Eigen::Vector2d normal;    // unit, image normal of the projected rim (an anchor: one image axis)
  Eigen::Vector2d observed;  // [px] edge position found on the search line
  double weight = 1.0;       // an anchor's weight relative to one rim sample
  bool rim = true;           // false: an anchor (not in the edge rms)
};

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

using Params = BoardPoseRefiner::Params;

/// The hole rims in the board frame: each hole's front (z = 0) and back
/// (z = -thickness) circle, sampled evenly, with the tangent at each sample.
struct Rims {
  std::vector<Eigen::Vector3d> points;    // [m] board frame, [hole][rim][theta]
  std::vector<Eigen::Vector3d> tangents;  // unit, board frame
  std::vector<int> hole;                  // the hole of each point
  std::array<Eigen::Vector2d, 4> centers;  // [m] hole centres, board frame
  double radius = 0.0;     // [m]
  double thickness = 0.0;  // [m]
};

Rims rims_of(const Target& target, int samples_per_rim) {
  Rims rims;
  rims.radius = target.hole_radius;
  rims.thickness = target.board_thickness;
  rims.centers = target.hole_centers();
  const int n = samples_per_rim;
  for (int h = 0; h < 4; ++h)
    for (const double z : {0.0, -rims.thickness})
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * M_PI * (k + 0.5) / n;
        rims.points.emplace_back(rims.centers[h].x() + rims.radius * std::cos(a),
                                 rims.centers[h].y() + rims.radius * std::sin(a), z);
        rims.tangents.emplace_back(-std::sin(a), std::cos(a), 0.0);
        rims.hole.push_back(h);
      }
  return rims;
}

/// The box around the rims' projection at pose T, padded by `pad` [px];
/// empty when no rim point projects (the board is behind the camera).
std::optional<cv::Rect> board_box(const View& view, const Rims& rims, const Eigen::Isometry3d& T, double pad) {
  double x_min = 1e18, y_min = 1e18, x_max = -1e18, y_max = -1e18;
  for (const auto& X : rims.points) {
    Eigen::Vector2d u;
    if (!view.project(T * X, u, nullptr)) continue;
    x_min = std::min(x_min, u.x()); x_max = std::max(x_max, u.x());
    y_min = std::min(y_min, u.y()); y_max = std::max(y_max, u.y());
  }
  if (x_min > x_max) return std::nullopt;
  return cv::Rect(cv::Point(static_cast<int>(x_min - pad), static_cast<int>(y_min - pad)),
                  cv::Point(static_cast<int>(x_max + pad), static_cast<int>(y_max + pad)));
}

/// The left view (and the right one, with use_right_image), each with the
/// gradient of the board's neighbourhood only: the whole image's would cost
/// more than the fit. Empty when the board is behind a camera.
std::vector<View> views_of(const StereoCamera& camera, const Image& left, const Image& right,
                           const cv::Mat& pixels_left, const cv::Mat& pixels_right, const Rims& rims,
                           const Eigen::Isometry3d& T_camera_board, const Params& params) {
  std::vector<View> views;
  const double baseline = camera.baseline();
  views.push_back({camera.left.projection_matrix, Eigen::Vector3d::Zero(), left.width, left.height, {}});
  if (params.use_right_image)
    views.push_back({camera.right.projection_matrix, Eigen::Vector3d(baseline, 0, 0), right.width,
                     right.height, {}});
  for (std::size_t v = 0; v < views.size(); ++v) {
    const double pad = 4.0 * params.search_range_px + 20.0;  // room for the pose to move
    const std::optional<cv::Rect> box = board_box(views[v], rims, T_camera_board, pad);
    if (!box) return {};
    views[v].grad = gradient_of(v == 0 ? pixels_left : pixels_right, *box);
  }
  return views;
}

/// True when the line of sight from `eye` through rim point X (board frame)
/// passes outside the hole's other rim circle: the hole's wall hides X.
bool hidden_by_wall(const Rims& rims, const Eigen::Vector3d& eye, const Eigen::Vector3d& X, int hole) {
  const double other_z = X.z() == 0.0 ? -rims.thickness : 0.0;
  const double s = (other_z - eye.z()) / (X.z() - eye.z());
  const Eigen::Vector3d Q = eye + s * (X - eye);
  return (Q.head<2>() - rims.centers[hole]).norm() > rims.radius;
}

/// Where a rim point projects in a view and the image normal of its rim there.
struct RimPixel {
  Eigen::Vector2d u;       // [px]
  Eigen::Vector2d normal;  // unit
};

/// The first edge from the board's side counts as the rim only when it is at
/// least this share of the strongest edge in the search window: weaker bumps
/// nearer the face are its texture or noise. On three random scenes before
/// tiles and bricks (1653306487, 1060328696, 2031326890; 3 frames each) 0.3
/// refined 9 of 9 frames to 0.3-4.5 mm; 0 refined 7 (two kept circles 6-7
/// mm off), 0.5 refined 6.
constexpr double kFirstEdgeShare = 0.3;

/// The search half of a round: which (view, rim point) samples are used, and
/// where each finds its edge along the rim's normal.
///
/// Visibility and the separation test are decided afresh while the search
/// range shrinks, then frozen (`locked`): samples toggling at those
/// thresholds would otherwise keep the pose jittering by a few 1e-5 and never
/// let the rounds settle. Once frozen, a sample that loses its edge (too
/// weak, window clipped) is dropped for good, so the set only shrinks and
/// cannot toggle either.
class EdgeSearch {
 public:
  EdgeSearch(const Params& params, const Rims& rims, const std::vector<View>& views)
      : params_(params), rims_(rims), views_(views), chosen_(views.size() * rims.points.size(), 0) {}

  /// Fills `samples` with the edges found at pose T within +-range [px];
  /// returns how many samples were searched (search line inside the image),
  /// edge or not.
  int search(const Eigen::Isometry3d& T, double range, bool locked, std::vector<Sample>& samples) {
    steps_ = static_cast<int>(std::floor(range / params_.search_step_px));
    profile_.assign(2 * steps_ + 1, 0.0);
    margin_ = params_.image_margin_px + range;
    samples.clear();
    int searched = 0;
    const Eigen::Isometry3d T_board_camera = T.inverse();
    for (std::size_t v = 0; v < views_.size(); ++v) {
      const View& view = views_[v];
      const Eigen::Vector3d eye = T_board_camera * view.center;  // camera centre, board frame
      if (!(eye.z() > 0.0)) continue;  // looking at the back face
      for (std::size_t k = 0; k < rims_.points.size(); ++k) {
        const Eigen::Vector3d& X = rims_.points[k];
        char& use = chosen_[v * rims_.points.size() + k];
        if (locked && !use) continue;
        use = 0;
        if (!locked && hidden_by_wall(rims_, eye, X, rims_.hole[k])) continue;
        RimPixel at;
        double along = 0.0;  // [px] edge position on the search line
        const Outcome outcome = find_edge(view, T, k, locked, at, along);
        if (outcome != Outcome::NotSearched) ++searched;
        if (outcome != Outcome::Edge) continue;
        use = 1;
        samples.push_back({static_cast<int>(v), X, at.normal, at.u + along * at.normal});
      }
    }
    return searched;
  }

 private:
  enum class Outcome { NotSearched, NoEdge, Edge };

  /// The edge of rim point k in `view` at pose T: its projection, the
  /// search window along the normal, the gradient profile and its peak.
  Outcome find_edge(const View& view, const Eigen::Isometry3d& T, std::size_t k, bool locked, RimPixel& at,
                    double& along) {
    const Eigen::Vector3d& X = rims_.points[k];
    if (!project_rim(view, T, k, at)) return Outcome::NotSearched;
    int lo = 0, hi = 2 * steps_;  // profile indices (offset -steps..steps)
    if (X.z() != 0.0 && !clip_back_rim_window(view, T, X, at, locked, lo, hi)) return Outcome::NotSearched;
    if (!sample_profile(view, at, lo, hi)) return Outcome::NotSearched;
    const int board_side = params_.first_edge_from_board ? board_side_of(view, T, k, at) : 0;
    return peak(lo, hi, board_side, along) ? Outcome::Edge : Outcome::NoEdge;
  }

  /// +1 when the board's material (the face beside a front rim, the hole's
  /// wall beside a back rim) lies along +normal from rim point k's
  /// projection, -1 when along -normal, 0 when it cannot be told.
  int board_side_of(const View& view, const Eigen::Isometry3d& T, std::size_t k, const RimPixel& at) const {
    const Eigen::Vector3d& X = rims_.points[k];
    const Eigen::Vector2d radial = (X.head<2>() - rims_.centers[rims_.hole[k]]).normalized();
    // The face lies outside the front rim; the wall of a back rim towards the front rim.
    const Eigen::Vector3d toward =
        X.z() == 0.0 ? Eigen::Vector3d(X.x() + 1e-3 * radial.x(), X.y() + 1e-3 * radial.y(), 0.0)
                     : Eigen::Vector3d(X.x(), X.y(), 0.0);
    Eigen::Vector2d u;
    if (!view.project(T * toward, u, nullptr)) return 0;
    const double side = at.normal.dot(u - at.u);
    return side > 0.0 ? 1 : side < 0.0 ? -1 : 0;
  }

  /// Projection and rim normal of rim point k; false when it falls outside
  /// the image (less the margin and the search range) or the rim is seen
  /// edge-on.
  bool project_rim(const View& view, const Eigen::Isometry3d& T, std::size_t k, RimPixel& at) const {
    Eigen::Matrix<double, 2, 3> J;
    const Eigen::Vector3d p = T * rims_.points[k];
    if (!view.project(p, at.u, &J)) return false;
    const double m = margin_;
    const Eigen::Vector2d& u = at.u;
    if (u.x() < m || u.y() < m || u.x() > view.width - 1 - m || u.y() > view.height - 1 - m) return false;
    const Eigen::Vector2d tangent = J * (T.linear() * rims_.tangents[k]);
    if (tangent.norm() < 1e-9) return false;
    at.normal = Eigen::Vector2d(-tangent.y() / tangent.norm(), tangent.x() / tangent.norm());
    return true;
  }

  /// A back-rim silhouette has the hole wall beside it, bounded by the front
  /// rim's edge (face | wall | back rim | background). When that band is
  /// narrow both edges merge into one gradient peak whose position is
  /// biased, differently in each view: such samples are dropped (until the
  /// selection is locked). The face-to-wall edge is often the stronger one (a
  /// wall in shadow is as dark as what is seen through the hole), so the
  /// search must not reach it: the window [lo, hi] stops half a pixel short
  /// of half-way to the front rim on that side, whatever the step (the Sobel
  /// response of that edge is ~1.5 px wide; a window ending on its flank
  /// finds a biased peak).
  bool clip_back_rim_window(const View& view, const Eigen::Isometry3d& T, const Eigen::Vector3d& X,
                            const RimPixel& at, bool locked, int& lo, int& hi) const {
    Eigen::Vector2d u_front;
    if (!view.project(T * Eigen::Vector3d(X.x(), X.y(), 0.0), u_front, nullptr)) return false;
    const double separation = at.normal.dot(u_front - at.u);  // [px] signed, along the normal
    if (!locked && std::abs(separation) < params_.min_rim_separation_px) return false;
    const int reach = std::max(
        1, static_cast<int>(std::floor((0.5 * std::abs(separation) - 0.5) / params_.search_step_px)));
    if (separation > 0.0)
      hi = std::min(hi, steps_ + reach);
    else
      lo = std::max(lo, steps_ - reach);
    return true;
  }

  /// |directional gradient| along the normal at profile indices lo..hi;
  /// false when the window leaves the gradient's crop.
  bool sample_profile(const View& view, const RimPixel& at, int lo, int hi) {
    const Eigen::Vector2d& u = at.u;
    const Eigen::Vector2d& normal = at.normal;
    bool inside = true;
    for (int i = lo; i <= hi && inside; ++i) {
      inside = view.grad.along(u.x() + (i - steps_) * params_.search_step_px * normal.x(),
                               u.y() + (i - steps_) * params_.search_step_px * normal.y(), normal, profile_[i]);
    }
    return inside;
  }

  /// The rim's peak in the profile, refined by a parabola, as a distance
  /// along the normal [px]; false when it is too weak or the profile still
  /// rises at a clipped end (the peak is the front rim's, beyond).
  ///
  /// With `board_side` (+1 / -1: the board's material lies towards higher /
  /// lower indices) it is the first peak met coming from the board's side,
  /// not the strongest: the board's face beside a rim is smooth, what is
  /// seen through the hole need not be. Bricks or tiles behind a hole put
  /// edges a pixel or two inside the rim that are stronger than a
  /// low-contrast rim, and the strongest peak then follows them: on a gray
  /// board before bricks (random scene 1037259372) a refinement started at
  /// the true pose did not converge and ended 31 mm and 4.7 deg off (1.8 mm,
  /// 0.23 deg and converged with this rule). A peak is a sample that is the
  /// largest within +-1 px and reaches min_edge_strength and kFirstEdgeShare
  /// of the strongest.
  bool peak(int lo, int hi, int board_side, double& along) const {
    const std::vector<double>& profile = profile_;
    int best = lo + 1;
    for (int i = lo + 1; i < hi; ++i)
      if (profile[i] > profile[best]) best = i;
    if (profile[best] < params_.min_edge_strength) return false;
    if ((lo > 0 && profile[lo] > profile[best]) || (hi < 2 * steps_ && profile[hi] > profile[best])) return false;
    if (board_side != 0)
      best = first_peak_from(board_side > 0 ? hi - 1 : lo + 1, -board_side, lo, hi,
                             std::max(params_.min_edge_strength, kFirstEdgeShare * profile[best]));
    const double a = profile[best - 1], b = profile[best], c = profile[best + 1];
    const double denom = a - 2.0 * b + c;
    const double offset = denom < 0.0 ? 0.5 * (a - c) / denom : 0.0;
    along = (best - steps_ + offset) * params_.search_step_px;
    return true;
  }

  /// The first inner index from `start`, walking by `step` (+-1), that
  /// reaches `threshold` and is the largest within +-1 px; the strongest
  /// sample does, so one is always found.
  int first_peak_from(int start, int step, int lo, int hi, double threshold) const {
    const int reach = std::max(1, static_cast<int>(std::lround(1.0 / params_.search_step_px)));
    for (int i = start; i > lo && i < hi; i += step) {
      if (profile_[i] < threshold) continue;
      bool largest = true;
      for (int j = std::max(lo, i - reach); j <= std::min(hi, i + reach) && largest; ++j)
        largest = profile_[j] <= profile_[i];
      if (largest) return i;
    }
    return start;
  }

  const Params& params_;
  const Rims& rims_;
  const std::vector<View>& views_;
  std::vector<char> chosen_;     // [view][rim point]: used in the last round
  std::vector<double> profile_;  // gradient along the current search line
  int steps_ = 0;                // search steps on each side of the rim
  double margin_ = 0.0;          // [px] from the image border, search range included
};

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

/// The Gauss-Newton increment (v, omega) for the signed normal distances of
/// the samples at pose T, Huber-weighted; `rms_px` gets their rms.
Eigen::Matrix<double, 6, 1> gauss_newton_delta(const std::vector<Sample>& samples, const std::vector<View>& views,
                                               const Eigen::Isometry3d& T, double huber_px, double& rms_px) {
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
    const double w = sample.weight * (std::abs(residual) <= huber_px ? 1.0 : huber_px / std::abs(residual));
    H += w * row.transpose() * row;
    g += w * row.transpose() * residual;
    if (!sample.rim) continue;
    sum_sq += residual * residual;
    sum_w += 1.0;
  }
  rms_px = std::sqrt(sum_sq / std::max(sum_w, 1.0));
  H.diagonal() *= 1.0 + 1e-9;  // keeps LDLT well defined if an axis is barely observed
  return -H.ldlt().solve(g);
}

/// How far one round moved the pose.
struct RoundMotion {
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();     // [rad] sum of the steps' omega
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // [m] sum of the steps' v
};

/// The fit half of a round: Gauss-Newton steps with the found edges held
/// fixed. Moves T; false when an update is not finite (T is then the pose
/// before that step).
bool fit_pose(const std::vector<Sample>& samples, const std::vector<View>& views, const Params& params,
              Eigen::Isometry3d& T, RoundMotion& motion, double& rms_px) {
  for (int step = 0; step < params.gauss_newton_steps; ++step) {
    const Eigen::Matrix<double, 6, 1> delta = gauss_newton_delta(samples, views, T, params.huber_px, rms_px);
    if (!delta.allFinite()) return false;
    const Eigen::Vector3d v = delta.head<3>(), w = delta.tail<3>();
    T = apply_increment(T, v, w);
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

/// The search-and-fit rounds from an initial pose. The search range halves
/// each round down to the final one, which then locks the sample selection
/// (EdgeSearch).
class Alignment {
 public:
  /// `anchors`: known points fitted with the rims in every round (marker corners of a mono camera).
  Alignment(const Params& params, const Rims& rims, const std::vector<View>& views, const std::vector<Sample>& anchors)
      : params_(params), rims_(rims), views_(views), anchors_(anchors), edges_(params, rims, views) {}

  /// Fills `result` (reason empty: converged) with the pose the rounds end at.
  void run(const Eigen::Isometry3d& T_camera_board, BoardPoseRefiner::Result& result) {
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

 private:
  /// One search and fit; false when the round fails (result.reason says why).
  bool run_round(int round, Eigen::Isometry3d& T, BoardPoseRefiner::Result& result) {
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

    samples_.insert(samples_.end(), anchors_.begin(), anchors_.end());
    const Eigen::Isometry3d T_round_start = T;
    RoundMotion motion;
    if (!fit_pose(samples_, views_, params_, T, motion, result.rms_px)) {
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

  const Params& params_;
  const Rims& rims_;
  const std::vector<View>& views_;
  const std::vector<Sample>& anchors_;
  EdgeSearch edges_;
  std::vector<Sample> samples_;  // the last round's edges (and the anchors)
  bool settled_ = false;
  bool lock_selection_ = false;  // the next round keeps this round's sample selection
  double previous_step_px_ = std::numeric_limits<double>::infinity();
  int searched_at_selection_ = 0;  // samples searched in the round that chose the selection
};

/// [gray levels / px] Sigma of the Sobel / 8 response to the noise of the
/// noisier image (its noisiest channel): white noise of sigma s gives
/// s * sqrt(12) / 8 per axis.
double gradient_noise(const cv::Mat& pixels_left, const cv::Mat& pixels_right) {
  const double noise = std::max(detail::image_noise_sigma(pixels_left), detail::image_noise_sigma(pixels_right));
  return noise * std::sqrt(12.0) / 8.0;
}

/// [gray levels / px] How strong the rims look at pose T: over the front-rim
/// samples of every view, the median of the strongest gradient along the
/// rim normal within +-search_range_px. 0 when no sample is inside a view.
double rim_contrast(const std::vector<View>& views, const Rims& rims, const Eigen::Isometry3d& T,
                    const Params& params) {
  std::vector<double> strongest;
  const double margin = params.image_margin_px + params.search_range_px;
  for (const View& view : views)
    for (std::size_t k = 0; k < rims.points.size(); ++k) {
      if (rims.points[k].z() != 0.0) continue;
      Eigen::Vector2d u;
      Eigen::Matrix<double, 2, 3> J;
      if (!view.project(T * rims.points[k], u, &J)) continue;
      if (u.x() < margin || u.y() < margin || u.x() > view.width - 1 - margin || u.y() > view.height - 1 - margin)
        continue;
      const Eigen::Vector2d tangent = J * (T.linear() * rims.tangents[k]);
      if (tangent.norm() < 1e-9) continue;
      const Eigen::Vector2d normal(-tangent.y() / tangent.norm(), tangent.x() / tangent.norm());
      double best = 0.0, value = 0.0;
      for (double t = -params.search_range_px; t <= params.search_range_px; t += params.search_step_px)
        if (view.grad.along(u.x() + t * normal.x(), u.y() + t * normal.y(), normal, value)) best = std::max(best, value);
      strongest.push_back(best);
    }
  if (strongest.empty()) return 0.0;
  std::nth_element(strongest.begin(), strongest.begin() + strongest.size() / 2, strongest.end());
  return strongest[strongest.size() / 2];
}

/// [gray levels / px] The weakest rim gradient accepted in this pair:
/// min_edge_strength, lowered for a board whose rims are weaker than usual
/// (rim_contrast_fraction of their contrast), never below the noise's
/// response (edge_noise_factor sigmas, and 0.5 for noiseless images).
double edge_strength(double rim_contrast, double gradient_noise, const Params& params) {
  const double noise_floor = std::max(0.5, params.edge_noise_factor * gradient_noise);
  return std::min(params.min_edge_strength, std::max(noise_floor, params.rim_contrast_fraction * rim_contrast));
}

/// Share of the samples on circles of 1.35 hole radii around the holes, on
/// the board's face, that find an edge as strong as a rim within the final
/// search range at pose T. A board's face between its rims is smooth (or has
/// weak grain), so a true fit finds far fewer edges there than on its rims;
/// a patch of brick or tile wall taken for the board has edges everywhere,
/// as many there as on the "rims" the fit put on it.
double face_edge_fraction(const Params& params, const Target& target, const std::vector<View>& views,
                          const Eigen::Isometry3d& T) {
  Target wider = target;
  wider.hole_radius *= 1.35;
  wider.board_thickness = 0.0;
  Rims control = rims_of(wider, params.samples_per_rim);
  for (std::size_t k = control.points.size(); k-- > 0;)  // one circle per hole suffices (no back rim)
    if (k % (2 * params.samples_per_rim) >= static_cast<std::size_t>(params.samples_per_rim)) {
      control.points.erase(control.points.begin() + static_cast<std::ptrdiff_t>(k));
      control.tangents.erase(control.tangents.begin() + static_cast<std::ptrdiff_t>(k));
      control.hole.erase(control.hole.begin() + static_cast<std::ptrdiff_t>(k));
    }
  EdgeSearch search(params, control, views);
  std::vector<Sample> samples;
  const int searched = search.search(T, params.final_search_range_px, false, samples);
  return searched > 0 ? static_cast<double>(samples.size()) / searched : 0.0;
}

/// The rounds with min_edge_strength, taking the strongest edge near each
/// rim; when they fail, again taking the first edge from the board's side
/// (first_edge_from_board); then the strongest edges once more with the
/// threshold lowered to the rims' own contrast (edge_strength()). The first
/// attempt that converges is kept, else the first one's failure: a
/// refinement that diverged there marks a wrong hypothesis
/// (camera_branch.cpp), and the first-edge rule can settle near such a pose
/// without converging (random scene 11: a brick-red board rolled 90 deg by
/// its circles, 32 % of the rims on an edge, where the strongest edges
/// diverged to rms 50 px). Not the first edge at the lowered threshold: the
/// first bump above 2-3 gray levels / px is found on any wall, and a patch of
/// tiled wall 5-6 m away converged as the board (random scene 1405632196).
BoardPoseRefiner::Result align(const Params& params, const std::vector<View>& views, const Rims& rims,
                               const std::vector<Sample>& anchors, const Eigen::Isometry3d& T_camera_board,
                               const cv::Mat& pixels_left, const cv::Mat& pixels_right) {
  const auto attempt = [&](const Params& p) {
    BoardPoseRefiner::Result result;
    result.T_camera_board = T_camera_board;
    result.edge_strength = p.min_edge_strength;
    result.edges_from_board_side = p.first_edge_from_board;
    Alignment(p, rims, views, anchors).run(T_camera_board, result);
    result.converged = result.reason.empty();
    return result;
  };
  Params strongest = params;
  strongest.first_edge_from_board = false;
  const BoardPoseRefiner::Result first = attempt(strongest);
  if (first.converged) return first;
  if (params.first_edge_from_board) {
    const BoardPoseRefiner::Result board_side = attempt(params);
    if (board_side.converged) return board_side;
  }
  // A weaker threshold only when the ordinary one failed: on a textured
  // board (wood grain) a lower one lets the grain beside the rims win the
  // search, and a refinement that converged at 6 would end ~7 mm off.
  const double weaker = edge_strength(rim_contrast(views, rims, T_camera_board, params),
                                      gradient_noise(pixels_left, pixels_right), params);
  if (!(weaker < params.min_edge_strength)) return first;
  strongest.min_edge_strength = weaker;
  const BoardPoseRefiner::Result retry = attempt(strongest);
  return retry.converged ? retry : first;
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
  if (!(rim_contrast_fraction >= 0.0 && rim_contrast_fraction <= 1.0))
    throw ParamError("rim_contrast_fraction", "must be 0..1");
  if (!(edge_noise_factor >= 0.0)) throw ParamError("edge_noise_factor", "must be >= 0");
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
  return refine_with_anchors(left, right, camera, target, T_camera_board, {}, 0.0);
}

BoardPoseRefiner::Result BoardPoseRefiner::refine_with_anchors(const Image& left, const Image& right,
                                                               const StereoCamera& camera, const Target& target,
                                                               const Eigen::Isometry3d& T_camera_board,
                                                               const std::vector<PointObservation>& points,
                                                               double point_weight) const {
  target.validate();
  // Each anchor point is two samples: its residual along each image axis.
  std::vector<Sample> anchors;
  for (const PointObservation& point : points)
    for (const Eigen::Vector2d& axis : {Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.0, 1.0)})
      anchors.push_back({0, point.X_board, axis, point.pixel, point_weight, false});
  detail::check_stereo_images(left, right, camera);
  const cv::Mat gray_left = detail::gray_mat(left, "left");
  const cv::Mat gray_right = detail::gray_mat(right, "right");
  Result result;
  result.T_camera_board = T_camera_board;
  if (!T_camera_board.matrix().allFinite()) {
    result.reason = "initial pose is not finite";
    return result;
  }
  const Rims rims = rims_of(target, params_.samples_per_rim);
  std::vector<View> views = views_of(camera, left, right, gray_left, gray_right, rims, T_camera_board, params_);
  if (views.empty()) {
    result.reason = "the board is behind a camera";
    return result;
  }
  result = align(params_, views, rims, anchors, T_camera_board, gray_left, gray_right);
  // A rim can differ from the face in hue more than in brightness (a gray
  // board before red bricks): when the gray images fail, colour ones are
  // tried, each sample taking its strongest channel. Only then, as that
  // costs three gradients and lets more texture compete with the rims.
  if (!result.converged && left.channels == 3 && right.channels == 3) {
    const cv::Mat colour_left = detail::pixel_mat(left, "left"), colour_right = detail::pixel_mat(right, "right");
    std::vector<View> colour = views_of(camera, left, right, colour_left, colour_right, rims, T_camera_board, params_);
    Result in_colour = align(params_, colour, rims, anchors, T_camera_board, colour_left, colour_right);
    if (in_colour.converged) {
      result = std::move(in_colour);
      views = std::move(colour);
    }
  }
  Params used = params_;
  used.min_edge_strength = result.edge_strength;
  result.face_edge_fraction = face_edge_fraction(used, target, views, result.T_camera_board);
  return result;
}

BoardPoseRefiner::Result BoardPoseRefiner::refine(const Image& image, const CameraInfo& camera,
                                                  const Target& target, const Eigen::Isometry3d& T_camera_board,
                                                  const std::vector<PointObservation>& points,
                                                  double point_weight) const {
  if (!(point_weight >= 0.0) || !std::isfinite(point_weight)) throw ParamError("point_weight", "must be >= 0");
  Params one_view = params_;
  one_view.use_right_image = false;
  // The pair's checks see the one image twice; only the left view is fitted.
  return BoardPoseRefiner(one_view).refine_with_anchors(
      image, image, StereoCamera{camera, camera, ImageKind::Rectified}, target, T_camera_board, points, point_weight);
}

}  // namespace l2s
