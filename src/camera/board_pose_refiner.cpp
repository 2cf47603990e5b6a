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
// This file holds the driver; the rounds of search and fit are in
// rim_alignment.hpp, the rim model in rim_model.hpp, the edge search in
// rim_edge_search.hpp.

#include <l2s/board_pose_refiner.hpp>

#include <l2s/error.hpp>

#include "camera/cv_image.hpp"
#include "camera/noise_level.hpp"
#include "camera/rim_alignment.hpp"
#include "camera/rim_edge_search.hpp"
#include "camera/rim_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace l2s {
namespace {

using detail::Alignment;
using detail::EdgeSearch;
using detail::OutlineNuisance;
using detail::SampleFit;
using detail::fit_of;
using detail::Rims;
using detail::Sample;
using detail::View;
using detail::rims_of;
using detail::views_of;

using Params = BoardPoseRefiner::Params;

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
      control.material.erase(control.material.begin() + static_cast<std::ptrdiff_t>(k));
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
/// without converging (a hypothesis rolled 90 deg by its circles, with a
/// third of the rims on an edge, where the strongest edges diverge to tens
/// of pixels). Not the first edge at the lowered threshold: the first bump
/// above 2-3 gray levels / px is found on any wall, and a patch of tiled
/// wall metres behind the board would converge as the board.
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

/// The second stage (Params::fit_board_outline): from the rims' pose, the
/// rims and the board's outer edges fitted together, in the final search
/// range with the first stage's edge rules, the outline with its own
/// nuisance (OutlineNuisance) so that it holds the tilt, not the range.
/// Kept only when most of the outline agrees with the rims (the share and
/// rms of its inliers, the rims' rms grown by at most max_outline_rim_growth):
/// an outline mostly hidden or lost against its background would otherwise
/// pull the holes off their rims.
void fit_with_outline(const Params& params, const Target& target, const Rims& rims, const std::vector<Sample>& anchors,
                      const StereoCamera& camera, const Image& left, const Image& right, const cv::Mat& pixels_left,
                      const cv::Mat& pixels_right, BoardPoseRefiner::Result& result) {
  const Rims all = detail::with_outline(rims, target, params.outline_samples, params.outline_corner_gap);
  const std::vector<View> views =
      views_of(camera, left, right, pixels_left, pixels_right, all, result.T_camera_board, params);
  if (views.empty()) return;
  Params p = params;
  p.search_range_px = p.final_search_range_px;
  p.first_edge_from_board = result.edges_from_board_side;
  p.min_edge_strength = result.edge_strength;
  BoardPoseRefiner::Result both;
  Alignment alignment(p, all, views, anchors);
  alignment.free_outline_nuisance();
  alignment.run(result.T_camera_board, both);
  const OutlineNuisance& nuisance = alignment.outline_nuisance();
  const SampleFit outline = fit_of(alignment.samples(), views, both.T_camera_board, nuisance, true);
  const SampleFit rims_fit = fit_of(alignment.samples(), views, both.T_camera_board, nuisance, false);
  result.outline_samples = outline.inliers;
  result.outline_rms_px = outline.rms_px;
  result.outline_disparity_bias_px = nuisance.disparity_px;
  result.outline_dilation = nuisance.dilation;
  std::ostringstream why;
  why.precision(3);
  if (!both.reason.empty())
    why << both.reason;
  else if (outline.inliers < params.min_samples || outline.inlier_share < params.min_outline_share)
    why << "only " << outline.inliers << " outline edge samples fit (" << std::lround(100.0 * outline.inlier_share)
        << " % of those found; need " << params.min_samples << " and " << std::lround(100.0 * params.min_outline_share)
        << " %)";
  else if (!(outline.rms_px <= params.max_outline_rms_px))
    why << "outline edge rms " << outline.rms_px << " px exceeds " << params.max_outline_rms_px << " px";
  else if (!(rims_fit.rms_px <= result.rms_px * params.max_outline_rim_growth))
    why << "the outline moves the rims: their rms " << result.rms_px << " -> " << rims_fit.rms_px << " px";
  result.outline_reason = why.str();
  if (!result.outline_reason.empty()) return;
  result.outline_used = true;
  result.T_camera_board = both.T_camera_board;
  result.centers = both.centers;
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
  if (outline_samples < 16 || outline_samples > 20000) throw ParamError("outline_samples", "must be 16..20000");
  if (!(outline_corner_gap >= 0.0)) throw ParamError("outline_corner_gap", "must be >= 0");
  if (!(max_outline_rms_px > 0.0)) throw ParamError("max_outline_rms_px", "must be > 0");
  if (!(max_outline_rim_growth >= 1.0)) throw ParamError("max_outline_rim_growth", "must be >= 1");
  if (!(min_outline_share >= 0.0 && min_outline_share <= 1.0)) throw ParamError("min_outline_share", "must be 0..1");
}

BoardPoseRefiner::BoardPoseRefiner(Params params) : params_(params) { params_.validate(); }

BoardPoseRefiner::Result BoardPoseRefiner::refine(const Image& left, const Image& right,
                                                  const StereoCamera& camera, const Target& target,
                                                  const Eigen::Isometry3d& T_camera_board) const {
  return refine_with_anchors(left, right, camera, target, T_camera_board, {}, {}, 0.0);
}

BoardPoseRefiner::Result BoardPoseRefiner::refine(const Image& left, const Image& right, const StereoCamera& camera,
                                                  const Target& target, const Eigen::Isometry3d& T_camera_board,
                                                  const std::vector<PointObservation>& left_points,
                                                  const std::vector<PointObservation>& right_points,
                                                  double point_weight) const {
  if (!(point_weight >= 0.0) || !std::isfinite(point_weight)) throw ParamError("point_weight", "must be >= 0");
  return refine_with_anchors(left, right, camera, target, T_camera_board, left_points,
                             params_.use_right_image ? right_points : std::vector<PointObservation>{}, point_weight);
}

BoardPoseRefiner::Result BoardPoseRefiner::refine_with_anchors(const Image& left, const Image& right,
                                                               const StereoCamera& camera, const Target& target,
                                                               const Eigen::Isometry3d& T_camera_board,
                                                               const std::vector<PointObservation>& left_points,
                                                               const std::vector<PointObservation>& right_points,
                                                               double point_weight) const {
  target.validate();
  // Each anchor point is two samples: its residual along each image axis, in
  // its view (0 left, 1 right).
  std::vector<Sample> anchors;
  for (const int view : {0, 1})
    for (const PointObservation& point : view == 0 ? left_points : right_points)
      for (const Eigen::Vector2d& axis : {Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d(0.0, 1.0)})
        anchors.push_back({view, point.X_board, axis, point.pixel, point_weight, false});
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
  const cv::Mat* pixels_left = &gray_left;
  const cv::Mat* pixels_right = &gray_right;
  // A rim can differ from the face in hue more than in brightness (a gray
  // board before red bricks): when the gray images fail, colour ones are
  // tried, each sample taking its strongest channel. Only then, as that
  // costs three gradients and lets more texture compete with the rims.
  cv::Mat colour_left, colour_right;
  if (!result.converged && left.channels == 3 && right.channels == 3) {
    colour_left = detail::pixel_mat(left, "left");
    colour_right = detail::pixel_mat(right, "right");
    std::vector<View> colour = views_of(camera, left, right, colour_left, colour_right, rims, T_camera_board, params_);
    Result in_colour = align(params_, colour, rims, anchors, T_camera_board, colour_left, colour_right);
    if (in_colour.converged) {
      result = std::move(in_colour);
      views = std::move(colour);
      pixels_left = &colour_left;
      pixels_right = &colour_right;
    }
  }
  Params used = params_;
  used.min_edge_strength = result.edge_strength;
  result.face_edge_fraction = face_edge_fraction(used, target, views, result.T_camera_board);
  if (result.converged && params_.fit_board_outline)
    fit_with_outline(params_, target, rims, anchors, camera, left, right, *pixels_left, *pixels_right, result);
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
      image, image, StereoCamera{camera, camera, ImageKind::Rectified}, target, T_camera_board, points, {},
      point_weight);
}

}  // namespace l2s
