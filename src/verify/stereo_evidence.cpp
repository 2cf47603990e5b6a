#include "verify/stereo_evidence.hpp"

#include "camera/cv_image.hpp"
#include "camera/noise_level.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace l2s::detail {
namespace {

/// The gray values of a (2k+1) x (2k+1) patch at a sub-pixel centre, with
/// their mean and standard deviation.
struct Patch {
  std::vector<double> values;
  double mean = 0.0, sigma = 0.0;
};

Patch sample_patch(const cv::Mat& image, const Eigen::Vector2d& c, int k) {
  Patch patch;
  double s = 0, ss = 0;
  for (int dy = -k; dy <= k; ++dy)
    for (int dx = -k; dx <= k; ++dx) {
      const double v = gray_at(image, c.x() + dx, c.y() + dy);
      patch.values.push_back(v);
      s += v, ss += v * v;
    }
  const double n = static_cast<double>(patch.values.size());
  patch.mean = s / n;
  patch.sigma = std::sqrt(std::max(0.0, ss / n - patch.mean * patch.mean));
  return patch;
}

/// The right image along one row band, resampled at the sub-pixel offset of
/// `centre`: the patches at centre - shift for every whole shift in
/// [lo, hi] share it, so each costs one pass over its values, not a
/// bilinear lookup per pixel and shift.
class RowStrip {
 public:
  RowStrip(const cv::Mat& image, const Eigen::Vector2d& centre, int k, int lo, int hi)
      : k_(k), hi_(hi), width_(hi - lo + 2 * k + 1), values_(static_cast<std::size_t>(width_ * (2 * k + 1))) {
    const double x0 = centre.x() - hi - k;  // column of shift hi's leftmost pixel
    for (int dy = -k; dy <= k; ++dy)
      for (int i = 0; i < width_; ++i)
        values_[static_cast<std::size_t>((dy + k) * width_ + i)] = gray_at(image, x0 + i, centre.y() + dy);
  }

  /// Zero-mean normalised cross-correlation of `patch` with the strip's
  /// patch at `shift` (centre.x - shift); NaN when either is flat.
  double zncc(const Patch& patch, int shift) const {
    const int offset = hi_ - shift;  // first column of that patch in the strip
    const int side = 2 * k_ + 1;
    double sb = 0, sbb = 0, sab = 0;
    for (int row = 0; row < side; ++row) {
      const double* b = &values_[static_cast<std::size_t>(row * width_ + offset)];
      const double* a = &patch.values[static_cast<std::size_t>(row * side)];
      for (int col = 0; col < side; ++col) sb += b[col], sbb += b[col] * b[col], sab += a[col] * b[col];
    }
    const double n = side * side;
    const double vb = sbb / n - (sb / n) * (sb / n);
    if (patch.sigma <= 1e-9 || vb <= 1e-9) return std::numeric_limits<double>::quiet_NaN();
    return (sab / n - patch.mean * (sb / n)) / (patch.sigma * std::sqrt(vb));
  }

 private:
  int k_, hi_, width_;
  std::vector<double> values_;
};

/// The best correlation over whole shifts in [lo, hi], leaving out those
/// within `exclusion` of 0 (the plane's own peak); -1 when none is finite.
double best_shift_score(const Patch& patch, const RowStrip& strip, int lo, int hi, int exclusion) {
  double best = -1.0;
  for (int shift = lo; shift <= hi; ++shift) {
    if (std::abs(shift) < exclusion) continue;
    const double score = strip.zncc(patch, shift);
    if (std::isfinite(score)) best = std::max(best, score);
  }
  return best;
}

/// What the views say at one place of the plane: +1 consistent, -1 not, 0 no
/// evidence. The left patch is matched against the right image along the
/// row, over the disparities around the plane's: the place lies on the plane
/// when the plane's disparity matches clearly best, and off it when another
/// disparity matches clearly better. A patch without contrast well above the
/// noise, a smooth ramp or a horizontal line (matches at any shift), or a
/// periodic texture (matches at several) gives no clear winner: no evidence.
/// `far_behind_px` (>= search_behind_px): how far behind the plane the
/// working range reaches. A place that looks consistent nearby is searched
/// that far as well: a repetitive wall far behind a hole matches at its true
/// disparity and, one period later, at the plane's; only the wide search
/// sees both.
int photo_vote(const cv::Mat& left, const cv::Mat& right, const Eigen::Vector2d& l, const Eigen::Vector2d& r,
               double min_sigma, int far_behind_px, const StereoEvidenceParams& p) {
  const int k = p.patch_radius;
  const int lo = -p.search_behind_px, hi = p.search_front_px;  // right-image shifts: behind the plane = +x
  const auto inside = [&](const Eigen::Vector2d& q, int margin_left, int margin_right) {
    return q.allFinite() && q.x() - margin_left >= k + 1 && q.y() >= k + 1 &&
           q.x() + margin_right < left.cols - k - 2 && q.y() < left.rows - k - 2;
  };
  if (!inside(l, 0, 0) || !inside(r, hi, -lo)) return 0;
  const Patch patch = sample_patch(left, l, k);
  if (patch.sigma < min_sigma) return 0;
  const RowStrip near(right, r, k, lo, hi);
  const double at_plane = near.zncc(patch, 0);
  if (!std::isfinite(at_plane)) return 0;
  const double best_other = best_shift_score(patch, near, lo, hi, p.exclusion_px);
  if (best_other >= p.consistent && best_other >= at_plane + p.margin) return -1;
  if (at_plane < p.consistent || at_plane < best_other + p.margin) return 0;
  // Consistent nearby: does a farther disparity match as well?
  const int far = std::min(far_behind_px, right.cols - k - 3 - static_cast<int>(std::ceil(r.x())));
  if (far <= p.search_behind_px) return +1;
  const RowStrip wide(right, r, k, -far, lo - 1);
  const double best_far = best_shift_score(patch, wide, -far, lo - 1, p.exclusion_px);
  if (best_far >= p.consistent && best_far >= at_plane + p.margin) return -1;
  if (best_far > at_plane - p.margin) return 0;
  return +1;
}

/// Board-frame sample positions on a square grid of `step` [m] within a region.
template <class Inside>
std::vector<Eigen::Vector2d> grid(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double step, int max_samples,
                                  Inside&& inside) {
  std::vector<Eigen::Vector2d> out;
  for (double y = lo.y(); y <= hi.y(); y += step)
    for (double x = lo.x(); x <= hi.x(); x += step)
      if (inside(Eigen::Vector2d(x, y))) out.emplace_back(x, y);
  if (static_cast<int>(out.size()) <= max_samples) return out;
  std::vector<Eigen::Vector2d> thinned;  // every k-th: spread over the region, deterministic
  const double stride = static_cast<double>(out.size()) / max_samples;
  for (int i = 0; i < max_samples; ++i) thinned.push_back(out[static_cast<std::size_t>(i * stride)]);
  return thinned;
}

/// The left image's gray values at board-frame places.
std::vector<double> gray_values(const cv::Mat& image, const CameraInfo& camera, const Eigen::Isometry3d& T_camera_board,
                                const std::vector<Eigen::Vector2d>& places) {
  std::vector<double> values;
  for (const auto& q : places) {
    const Eigen::Vector2d px = camera.project(T_camera_board * Eigen::Vector3d(q.x(), q.y(), 0.0));
    if (px.allFinite() && px.x() >= 0 && px.y() >= 0 && px.x() < image.cols - 1 && px.y() < image.rows - 1)
      values.push_back(gray_at(image, px.x(), px.y()));
  }
  return values;
}

/// Median and robust spread (1.4826 MAD) of `values` (not empty).
std::pair<double, double> median_and_spread(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  const double median = *middle;
  for (double& v : values) v = std::abs(v - median);
  std::nth_element(values.begin(), middle, values.end());
  return {median, 1.4826 * *middle};
}

/// How far apart the typical brightness of two surfaces is, in their
/// combined robust spread (at least `floor` gray levels); 0 when either has
/// too few values to say.
double look_difference(const std::vector<double>& a, const std::vector<double>& b, double floor) {
  constexpr std::size_t kMinValues = 5;
  if (a.size() < kMinValues || b.size() < kMinValues) return 0.0;
  const auto [median_a, spread_a] = median_and_spread(a);
  const auto [median_b, spread_b] = median_and_spread(b);
  return std::abs(median_a - median_b) / std::max(floor, std::hypot(spread_a, spread_b));
}

}  // namespace

BoardEvidence stereo_evidence(const cv::Mat& left, const cv::Mat& right, const StereoCamera& cameras,
                              const Eigen::Isometry3d& T_camera_board, const Target& target,
                              const BoardVerifier::Params& verifier, const StereoEvidenceParams& params) {
  BoardEvidence evidence;
  const double min_sigma = std::max(params.min_contrast, params.noise_factor * image_noise_sigma(left));
  const double depth = std::max(0.1, T_camera_board.translation().z());
  const double step = params.sample_step_px * depth / cameras.left.fx();
  // The disparity of the working range's farthest depth: how far behind the
  // plane a background can match.
  const double min_disparity = cameras.right.fx() * cameras.baseline() / params.max_depth;
  const auto vote = [&](const Eigen::Vector2d& q) {
    const Eigen::Vector3d p = T_camera_board * Eigen::Vector3d(q.x(), q.y(), 0.0);
    const Eigen::Vector2d l = cameras.left.project(p), r = cameras.right.project(p);
    const double behind = std::min<double>(params.max_search_behind_px, (l.x() - r.x()) - min_disparity);
    const int far_behind = std::isfinite(behind) ? std::max(params.search_behind_px, static_cast<int>(behind)) : 0;
    return photo_vote(left, right, l, r, min_sigma, far_behind, params);
  };
  // A sample's patch must not reach the rim or the board's border: their
  // edges match at the board's disparity whatever lies behind.
  const double patch_reach = (params.patch_radius + 1) * depth / cameras.left.fx();
  const double open_radius = target.hole_radius - verifier.hole_margin - patch_reach;
  const auto holes = target.hole_centers();
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector2d c = holes[h], reach = Eigen::Vector2d::Constant(open_radius);
    const auto samples = grid(c - reach, c + reach, step, params.max_samples,
                              [&](const Eigen::Vector2d& q) { return (q - c).norm() < open_radius; });
    for (const auto& q : samples) {
      const int v = vote(q);
      if (v > 0) ++evidence.hole_blocked[h];
      if (v < 0) ++evidence.hole_open[h];
    }
    // The face just outside the rim, inside the board's outline.
    const double face_from = target.hole_radius + verifier.hole_margin + patch_reach;
    const double face_to = face_from + params.face_band;
    const Eigen::Vector2d face_reach = Eigen::Vector2d::Constant(face_to);
    const auto face = grid(c - face_reach, c + face_reach, step, params.max_samples, [&](const Eigen::Vector2d& q) {
      const double r = (q - c).norm();
      return r > face_from && r < face_to && std::abs(q.x()) < 0.5 * target.board_width - patch_reach &&
             std::abs(q.y()) < 0.5 * target.board_height - patch_reach;
    });
    evidence.hole_look_difference[h] = look_difference(gray_values(left, cameras.left, T_camera_board, samples),
                                                       gray_values(left, cameras.left, T_camera_board, face), min_sigma);
  }
  const Eigen::Vector2d inner(0.5 * target.board_width + verifier.outline_gap + patch_reach,
                              0.5 * target.board_height + verifier.outline_gap + patch_reach);
  const Eigen::Vector2d outer = inner + Eigen::Vector2d::Constant(verifier.outline_width);
  const auto band = grid(-outer, outer, step, params.max_samples, [&](const Eigen::Vector2d& q) {
    return std::abs(q.x()) > inner.x() || std::abs(q.y()) > inner.y();
  });
  for (const auto& q : band) {
    const int v = vote(q);
    if (v > 0) ++evidence.outline_blocked;
    if (v < 0) ++evidence.outline_open;
  }
  return evidence;
}

}  // namespace l2s::detail
