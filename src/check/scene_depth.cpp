// Lidar returns of the whole scene against the coarse stereo depth of the
// left image (calibration_check.hpp): the share that agrees, the median
// relative difference, and the tilt between the two depths. A rotation error
// theta about the camera's x or y axis changes a point's depth by about
// theta times its lateral offset, so the relative depth difference grows
// linearly across the image with slope theta, whatever the translation:
// the tilt measures a rotation on the scene off the board, where a fit that
// followed a moving board (or the board alone) is wrong. It is fitted on the
// largest plane off the board (a wall, the ground), where coarse stereo's
// bias is nearly uniform.

#include "check/scene_scorer.hpp"

#include "check/board_geometry.hpp"

#include <random>
#include <unordered_map>
#include <utility>

namespace l2s::detail {
namespace {

struct VisibleReturn {
  Eigen::Vector3d p_lidar;
  double u, v;   // [px]
  double depth;  // [m] rectified frame
};

/// The returns the camera can see: each projects into the image and is not
/// hidden behind a nearer return of its cell (a z-buffer on cells of
/// kCell px). Lidar and camera look from different places, so the lidar
/// sees surfaces the camera does not (through the holes, behind the board's
/// edges); compared with stereo they would count against a right transform.
std::vector<VisibleReturn> visible_returns(const LidarProjector& projector, const std::vector<Eigen::Vector3d>& points) {
  constexpr double kCell = 16.0;  // [px] about the spacing of returns along a ring at the board
  std::vector<VisibleReturn> seen;
  double u, v;
  for (const auto& p : points)
    if (projector.project(p, u, v) && projector.inside(u, v)) seen.push_back({p, u, v, projector.depth(p)});
  std::unordered_map<long, double> nearest;
  const auto cell = [&](const VisibleReturn& r) {
    return (static_cast<long>(r.v / kCell) << 20) + static_cast<long>(r.u / kCell);
  };
  for (const auto& r : seen) {
    const auto [it, added] = nearest.emplace(cell(r), r.depth);
    if (!added) it->second = std::min(it->second, r.depth);
  }
  std::vector<VisibleReturn> out;
  for (const auto& r : seen)
    if (r.depth <= 1.05 * nearest[cell(r)] + 0.1) out.push_back(r);
  return out;
}

/// One lidar return compared with stereo, off the board.
struct DepthSample {
  Eigen::Vector3d p_camera;  // [m] the lidar return in the camera frame
  double x, y;               // normalised image coordinates (rectified frame)
  double relative;           // (lidar - stereo) / stereo
  int frame;                 // index of its frame among the depth frames
  bool textured;             // stereo measured its pixel (DepthMap::textured_at)
};

/// The samples on the largest plane of the lidar returns (5 cm), found by
/// a seeded RANSAC. SGBM's sub-pixel bias depends on the disparity, so
/// stereo is off by a different share on each surface (a wall, the ground);
/// on one plane the bias varies smoothly and hardly tilts.
std::vector<DepthSample> dominant_plane(const std::vector<DepthSample>& samples) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::size_t> pick(0, samples.size() - 1);
  std::vector<DepthSample> best;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const Eigen::Vector3d& a = samples[pick(rng)].p_camera;
    const Eigen::Vector3d n = (samples[pick(rng)].p_camera - a).cross(samples[pick(rng)].p_camera - a);
    if (n.norm() < 1e-6) continue;
    std::vector<DepthSample> inliers;
    for (const DepthSample& s : samples)
      if (std::abs(n.normalized().dot(s.p_camera - a)) < 0.05) inliers.push_back(s);
    if (inliers.size() > best.size()) best = std::move(inliers);
  }
  return best;
}

/// The normal equations of value(s) = a + b x + c y over the samples, each
/// weighted by Tukey's biweight (at 3 %) of its residual from `fit`, a fit of
/// the relative depth difference.
template <class Value>
std::pair<Eigen::Matrix3d, Eigen::Vector3d> biweighted_system(const std::vector<DepthSample>& samples,
                                                               const Eigen::Vector3d& fit, Value&& value) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const DepthSample& s : samples) {
    const Eigen::Vector3d row(1.0, s.x, s.y);
    const double r = (s.relative - row.dot(fit)) / 0.03;
    const double w = std::abs(r) < 1.0 ? (1.0 - r * r) * (1.0 - r * r) : 0.0;
    A += w * row * row.transpose();
    b += w * row * value(s);
  }
  return {A, b};
}

/// The slope (b, c) of relative = a + b x + c y on `samples`, refined from
/// `fit` by iteratively reweighted least squares; false when an image
/// direction has too little spread (about +-0.1 of the focal length) to give one.
bool fit_slope(const std::vector<DepthSample>& samples, Eigen::Vector3d& fit, int iterations) {
  for (int iteration = 0; iteration < iterations; ++iteration) {
    const auto [A, b] = biweighted_system(samples, fit, [](const DepthSample& s) { return s.relative; });
    if (!(A(1, 1) / A(0, 0) >= 0.005 && A(2, 2) / A(0, 0) >= 0.005)) return false;
    fit = A.ldlt().solve(b);
  }
  return true;
}

/// The tilt and its frame-to-frame uncertainty, both [rad], and the share
/// of the plane's samples on texture.
struct Tilt {
  double value = CalibrationCheck::Scores::kNaN;
  double sigma = CalibrationCheck::Scores::kNaN;
  double texture = CalibrationCheck::Scores::kNaN;
};

/// A tilt is measured only on a plane with stereo texture under at least
/// this share of its samples. A brick wall far behind the board has a
/// textured window at each joint across the rows, 33-37 % of its returns,
/// and SGBM's paths carry those matches over the flat bricks between them
/// (a wrong result of 172 mm / 3.2 deg showed its 3.2 deg tilt there); a
/// plain wall has 0-3 %.
constexpr double kMinTiltTexture = 0.15;

/// The standard error of the slope's length, by a delete-one-frame
/// jackknife: stereo noise and SGBM's mismatches differ from image pair to
/// image pair, so frames disagree on the slope by what they add to it, while
/// a rotation error tilts every frame alike. NaN with fewer than 3 frames.
double slope_sigma(const std::vector<DepthSample>& samples, const Eigen::Vector3d& fit, int frames) {
  if (frames < 3) return CalibrationCheck::Scores::kNaN;
  const Eigen::Vector2d slope = fit.tail<2>();
  if (slope.norm() == 0.0) return 0.0;
  const Eigen::Vector2d along = slope.normalized();
  std::vector<double> lengths;
  for (int left_out = 0; left_out < frames; ++left_out) {
    std::vector<DepthSample> kept;
    for (const DepthSample& s : samples)
      if (s.frame != left_out) kept.push_back(s);
    Eigen::Vector3d partial = fit;
    if (kept.size() < 100 || !fit_slope(kept, partial, 3)) continue;
    lengths.push_back(along.dot(partial.tail<2>()));
  }
  const double n = static_cast<double>(lengths.size());
  if (n < 3) return CalibrationCheck::Scores::kNaN;
  double mean = 0.0, spread = 0.0;
  for (double l : lengths) mean += l / n;
  for (double l : lengths) spread += (l - mean) * (l - mean);
  return std::sqrt((n - 1.0) / n * spread);
}

/// [rad] The tilt of the relative depth difference across the image on the
/// largest plane: a robust fit of relative = a + b x + c y (Tukey's
/// biweight at 3 %, from the median: stereo smeared over from a nearer
/// surface must not count at all); atan of |(b, c)|, less what a disparity
/// bias alone can tilt there. A bias of delta px makes stereo off by
/// delta z / (f B) of the depth, which on a plane slanted away from the
/// camera (the ground, a wall seen obliquely) grows across the image as the
/// depth does: a tilt of delta / (f B) |grad z| that no rotation caused. A
/// bias of up to one matching sigma (`depth_noise` = sigma / (f B), 1/m) is
/// discounted, so a slanted plane shows a rotation only beyond it. NaN with
/// fewer than 100 samples, too little spread or too little texture (below
/// kMinTiltTexture). Its sigma: slope_sigma.
Tilt depth_tilt(const std::vector<DepthSample>& all, double depth_noise, int frames) {
  if (all.size() < 100) return {};
  const std::vector<DepthSample> samples = dominant_plane(all);
  if (samples.size() < 100) return {};
  Tilt tilt;
  std::size_t textured = 0;
  for (const DepthSample& s : samples) textured += s.textured;
  tilt.texture = static_cast<double>(textured) / static_cast<double>(samples.size());
  // A plane stereo did not measure holds SGBM's fill-in, which slopes
  // towards the nearer surfaces around it: a plain wall behind the board
  // tilted 20 deg against a right transform's lidar depths (random scene
  // 1262151257: 3 % of its returns on texture; textured walls and ground
  // 72-76 %, bricks 33-37 %).
  if (tilt.texture < kMinTiltTexture) return tilt;
  std::vector<double> relative;
  for (const DepthSample& s : samples) relative.push_back(s.relative);
  Eigen::Vector3d x(median(relative), 0.0, 0.0);
  if (!fit_slope(samples, x, 10)) return tilt;
  // The depth's gradient across the image on the same samples, same weights.
  const auto [A, b] = biweighted_system(samples, x, [](const DepthSample& s) { return s.p_camera.z(); });
  const Eigen::Vector3d z = A.ldlt().solve(b);
  const double bias_tilt = depth_noise * std::hypot(z[1], z[2]);
  tilt.value = std::atan(std::max(0.0, std::hypot(x[1], x[2]) - bias_tilt));
  tilt.sigma = std::atan(slope_sigma(samples, x, frames));
  return tilt;
}

}  // namespace

void SceneScorer::depth(const Eigen::Isometry3d& T_camera_lidar, CalibrationCheck::Scores& scores) const {
  const LidarProjector projector(view_, T_camera_lidar);
  int agree = 0, compared = 0;
  std::vector<double> relative;  // (lidar - stereo) / stereo of the returns within 20 %
  std::vector<DepthSample> off_board;
  for (std::size_t f = 0; f < depth_frames_.size(); ++f) {
    const CheckFrame* frame = depth_frames_[f];
    const DepthMap& map = frame->camera.depth;
    for (const VisibleReturn& r : visible_returns(projector, frame->lidar.scene)) {
      const Eigen::Vector3d p_camera = T_camera_lidar * r.p_lidar;
      const auto& T_camera_board = frame->camera.T_camera_board;
      if (T_camera_board && behind_board(p_camera, *T_camera_board, target_)) continue;
      const double stereo = map.at(r.u, r.v);
      if (!std::isfinite(stereo)) continue;
      const double sigma = map.depth_noise * stereo * stereo;
      ++compared;
      agree += std::abs(r.depth - stereo) <= params_.depth_tolerance * stereo + 3.0 * sigma;
      if (!(std::abs(r.depth - stereo) < 0.2 * stereo)) continue;
      relative.push_back((r.depth - stereo) / stereo);
      if (!T_camera_board || !near_board(p_camera, *T_camera_board, target_))
        off_board.push_back({p_camera, (r.u - view_.P(0, 2)) / view_.P(0, 0), (r.v - view_.P(1, 2)) / view_.P(1, 1),
                             relative.back(), static_cast<int>(f), map.textured_at(r.u, r.v)});
    }
  }
  scores.depth_points = compared;
  if (relative.size() >= 30) scores.depth_bias = median(relative);
  std::vector<double> noise;
  for (const CheckFrame* frame : depth_frames_) noise.push_back(frame->camera.depth.depth_noise);
  if (!noise.empty()) {
    const Tilt tilt = depth_tilt(off_board, median(noise), depth_frames());
    scores.depth_tilt = tilt.value;
    scores.depth_tilt_sigma = tilt.sigma;
    scores.depth_tilt_texture = tilt.texture;
  }
  scores.depth_agreement = compared > 0 ? static_cast<double>(agree) / compared : CalibrationCheck::Scores::kNaN;
}

}  // namespace l2s::detail
