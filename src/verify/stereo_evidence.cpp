#include "verify/stereo_evidence.hpp"

#include "camera/noise_level.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace l2s::detail {
namespace {

/// Bilinear gray value; the caller keeps (x, y) one pixel inside the image.
double bilinear(const cv::Mat& image, double x, double y) {
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  const double fx = x - ix, fy = y - iy;
  const std::uint8_t* r0 = image.ptr<std::uint8_t>(iy) + ix;
  const std::uint8_t* r1 = image.ptr<std::uint8_t>(iy + 1) + ix;
  return (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
}

/// Zero-mean normalised cross-correlation of two 7x7-like patches (bilinear
/// centres); NaN when either is flat.
double zncc(const cv::Mat& a_image, const Eigen::Vector2d& a, const cv::Mat& b_image, const Eigen::Vector2d& b,
            int k) {
  const int n = (2 * k + 1) * (2 * k + 1);
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int dy = -k; dy <= k; ++dy)
    for (int dx = -k; dx <= k; ++dx) {
      const double u = bilinear(a_image, a.x() + dx, a.y() + dy);
      const double v = bilinear(b_image, b.x() + dx, b.y() + dy);
      sa += u, sb += v, saa += u * u, sbb += v * v, sab += u * v;
    }
  const double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
  if (va <= 1e-9 || vb <= 1e-9) return std::numeric_limits<double>::quiet_NaN();
  return (sab / n - (sa / n) * (sb / n)) / std::sqrt(va * vb);
}

/// Standard deviation of a patch [gray levels].
double patch_sigma(const cv::Mat& image, const Eigen::Vector2d& c, int k) {
  const int n = (2 * k + 1) * (2 * k + 1);
  double s = 0, ss = 0;
  for (int dy = -k; dy <= k; ++dy)
    for (int dx = -k; dx <= k; ++dx) {
      const double v = bilinear(image, c.x() + dx, c.y() + dy);
      s += v, ss += v * v;
    }
  return std::sqrt(std::max(0.0, ss / n - (s / n) * (s / n)));
}

/// What the views say at one place of the plane: +1 consistent, -1 not, 0 no
/// evidence. The left patch is matched against the right image along the
/// row, over the disparities around the plane's: the place lies on the plane
/// when the plane's disparity matches clearly best, and off it when another
/// disparity matches clearly better. A patch without contrast well above the
/// noise, a smooth ramp or a horizontal line (matches at any shift), or a
/// periodic texture (matches at several) gives no clear winner: no evidence.
int photo_vote(const cv::Mat& left, const cv::Mat& right, const Eigen::Vector2d& l, const Eigen::Vector2d& r,
               double min_sigma, const StereoEvidenceParams& p) {
  const int k = p.patch_radius;
  const int lo = -p.search_behind_px, hi = p.search_front_px;  // right-image shifts: behind the plane = +x
  const auto inside = [&](const Eigen::Vector2d& q, int margin_left, int margin_right) {
    return q.allFinite() && q.x() - margin_left >= k + 1 && q.y() >= k + 1 &&
           q.x() + margin_right < left.cols - k - 2 && q.y() < left.rows - k - 2;
  };
  if (!inside(l, 0, 0) || !inside(r, hi, -lo)) return 0;
  if (patch_sigma(left, l, k) < min_sigma) return 0;
  const double at_plane = zncc(left, l, right, r, k);
  if (!std::isfinite(at_plane)) return 0;
  double best_other = -1.0;
  for (int shift = lo; shift <= hi; ++shift) {
    if (std::abs(shift) < p.exclusion_px) continue;
    const double score = zncc(left, l, right, r + Eigen::Vector2d(-shift, 0.0), k);
    if (std::isfinite(score)) best_other = std::max(best_other, score);
  }
  if (at_plane >= p.consistent && at_plane >= best_other + p.margin) return +1;
  if (best_other >= p.consistent && best_other >= at_plane + p.margin) return -1;
  return 0;
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

}  // namespace

BoardEvidence stereo_evidence(const cv::Mat& left, const cv::Mat& right, const StereoCamera& cameras,
                              const Eigen::Isometry3d& T_camera_board, const Target& target,
                              const BoardVerifier::Params& verifier, const StereoEvidenceParams& params) {
  BoardEvidence evidence;
  const double min_sigma = std::max(params.min_contrast, params.noise_factor * image_noise_sigma(left));
  const double depth = std::max(0.1, T_camera_board.translation().z());
  const double step = params.sample_step_px * depth / cameras.left.fx();
  const auto vote = [&](const Eigen::Vector2d& q) {
    const Eigen::Vector3d p = T_camera_board * Eigen::Vector3d(q.x(), q.y(), 0.0);
    return photo_vote(left, right, cameras.left.project(p), cameras.right.project(p), min_sigma, params);
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
