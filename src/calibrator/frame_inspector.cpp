// One frame through one branch with every stage's result kept, and a readable
// account of it: what each stage found, why it stopped, and the thresholds
// (Calibrator::Params fields) that decided it.

#include <l2s/frame_inspector.hpp>

#include "calibrator/branches.hpp"
#include "detail/input_checks.hpp"
#include "detail/plane_frame.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <string>

namespace l2s {
namespace {


double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// printf into a std::string.
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void append(std::string& out, const char* format, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  if (n > 0)
    out.append(buffer, std::min<std::size_t>(static_cast<std::size_t>(n), sizeof(buffer) - 1));
}

std::string limit(double value, const char* unit = "") {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.2f%s", value, unit);
  return buffer;
}

const char* yes_no(bool value) { return value ? "yes" : "no"; }

double degrees(double radians) { return radians * 180.0 / M_PI; }

// Angle of the plane from the sensor's vertical axis (what max_angle bounds).
double tilt_deg(const Plane& plane, const Eigen::Vector3d& up) {
  return degrees(std::asin(std::min(1.0, std::abs(plane.normal().dot(up.normalized())))));
}

void describe_status(std::string& out, const char* sensor, const BranchReport& report) {
  if (report.found)
    append(out, "%-7s FOUND: four labelled hole centres (%.1f ms)\n", sensor, report.milliseconds);
  else
    append(out, "%-7s FAILED at %s: %s (%.1f ms)\n", sensor, report.failed_stage.c_str(),
           report.reason.c_str(), report.milliseconds);
  if (!report.note.empty()) append(out, "  note: %s\n", report.note.c_str());
}

void describe_pass_through(std::string& out, const std::optional<PassThroughFilter::Result>& result,
                           std::size_t input, const PassThroughFilter::Params& p,
                           const char* field) {
  if (!result) return;
  append(out,
         "  pass-through     %zu of %zu points kept; dropped %zu non-finite, %zu outside the box, "
         "%zu outside the range\n",
         result->kept.size(), input, result->dropped_non_finite, result->dropped_box,
         result->dropped_range);
  append(out, "                   [%s: box x %s..%s, y %s..%s, z %s..%s m; range %s..%s m]\n",
         field, limit(p.min_xyz.x()).c_str(), limit(p.max_xyz.x()).c_str(),
         limit(p.min_xyz.y()).c_str(), limit(p.max_xyz.y()).c_str(), limit(p.min_xyz.z()).c_str(),
         limit(p.max_xyz.z()).c_str(), limit(p.min_range).c_str(), limit(p.max_range).c_str());
}

void describe_plane(std::string& out, const std::optional<PlaneSegmenter::Result>& result,
                    const PlaneSegmenter::Params& p, const char* field) {
  if (!result) return;
  const auto& r = *result;
  if (r.found)
    append(out, "  plane            %zu candidates, %zu board-sized (hypotheses, most board-like first)\n",
           r.candidates.size(), r.ranking.size());
  else if (r.candidates.empty())
    append(out, "  plane            no board plane: %s\n", r.reason.c_str());
  else
    append(out, "  plane            no board-sized plane among %zu candidates (each below)\n", r.candidates.size());
  append(out,
         "                   [%s: distance_threshold %.3f m, inlier_threshold %.3f m, max_angle "
         "%.3f rad (%.1f deg), size_tolerance %.2f, min_support %zu, max_candidates %d]\n",
         field, p.distance_threshold, p.inlier_threshold, p.max_angle, degrees(p.max_angle),
         p.size_tolerance, p.min_support, p.max_candidates);
  for (std::size_t i = 0; i < r.candidates.size(); ++i) {
    const auto& c = r.candidates[i];
    const Eigen::Vector3d n = c.plane.normal();
    append(out,
           "    candidate #%zu   n (%.3f, %.3f, %.3f), d %.3f m, %.1f deg from vertical, support "
           "%zu, patch %zu points %.2f x %.2f m: ",
           i, n.x(), n.y(), n.z(), c.plane.offset(), tilt_deg(c.plane, p.axis), c.support,
           c.patch_points, c.extent_long, c.extent_short);
    if (c.plausible)
      append(out, "board-sized, isolation %.2f, prior %.2f\n", c.isolation, c.prior);
    else
      append(out, "not the board: %s\n", c.reason.c_str());
  }
}

// The board-sized planes the branch tried, and why each won or lost.
void describe_hypotheses(std::string& out, const std::vector<BoardHypothesis>& hypotheses,
                         const BoardVerifier::Params& p, const char* field) {
  if (hypotheses.empty()) return;
  append(out, "  verify           %zu hypothesis(es) tried\n", hypotheses.size());
  append(out,
         "                   [%s: hole_margin %.3f m, min_hole_open %.2f, min_look_difference %.1f, min_outline_open %.2f, "
         "min_rim_support %.2f, min_rim_excess %.2f, min_samples %d, confident_score %.2f, max_hypotheses %d, "
         "challenger_prior %.2f]\n",
         field, p.hole_margin, p.min_hole_open, p.min_look_difference, p.min_outline_open, p.min_rim_support, p.min_rim_excess,
         p.min_samples, p.confident_score, p.max_hypotheses, p.challenger_prior);
  for (const BoardHypothesis& h : hypotheses) {
    const BoardEvidence& e = h.evidence;
    append(out, "    plane #%-2d (prior %.2f): %s%s: %s\n", h.candidate, h.prior,
           h.chosen ? "CHOSEN" : h.verified ? "verified" : "rejected at ", h.verified ? "" : h.stage.c_str(),
           h.reason.c_str());
    if (h.stage.empty() || h.stage == "verify" || h.stage == "refine") {  // holes were found: evidence exists
      append(out,
             "                   holes open/blocked TL %d/%d TR %d/%d BL %d/%d BR %d/%d, outline "
             "open/blocked %d/%d\n",
             e.hole_open[0], e.hole_blocked[0], e.hole_open[1], e.hole_blocked[1], e.hole_open[2],
             e.hole_blocked[2], e.hole_open[3], e.hole_blocked[3], e.outline_open, e.outline_blocked);
      const auto& look = e.hole_look_difference;
      if (look[0] + look[1] + look[2] + look[3] > 0.0)
        append(out, "                   inside unlike the face around (sigmas) TL %.1f TR %.1f BL %.1f BR %.1f\n",
               look[0], look[1], look[2], look[3]);
    }
  }
}

// Circle candidates in board-plane coordinates, the labelled holes and the thresholds.
void describe_circles(std::string& out, const std::optional<CircleFinder::Result>& result,
                      const Plane& plane, const Eigen::Vector3d& up, const Eigen::Vector3d& centre,
                      const CircleFinder::Params& p, const char* field, double rms_unit,
                      const char* rms_name) {
  if (!result) return;
  const auto& r = *result;
  if (r.found)
    append(out,
           "  circles          %zu candidates, four holes %s; fit rms %.1f %s over %zu "
           "points, pattern roll %.1f deg\n",
           r.candidates.size(),
           r.by_pattern_votes ? "found by the pattern's votes (no four candidates formed it)" : "matched",
           r.rms * rms_unit, rms_name, r.fit_points, degrees(r.pattern_angle));
  else
    append(out, "  circles          %zu candidates; no four holes: %s\n", r.candidates.size(),
           r.reason.c_str());
  append(out,
         "                   [%s: inlier_threshold %.3f m, min_circle_points %d, spacing_tolerance "
         "%.3f m, max_candidates %d, joint_fit %s]\n",
         field, p.inlier_threshold, p.min_circle_points, p.spacing_tolerance, p.max_candidates,
         yes_no(p.joint_fit));
  if (r.candidates.empty()) return;
  const auto frame = detail::PlaneFrame::make(plane, up, centre);
  append(out, "    (u right, v up in the board plane from the board points' centroid)\n");
  for (std::size_t i = 0; i < r.candidates.size(); ++i) {
    const Eigen::Vector2d q = frame.to_plane(r.candidates[i].center);
    std::string label;
    for (int h = 0; h < 4; ++h)
      if (r.matched[h] == static_cast<int>(i)) label = std::string("-> ") + hole_name(static_cast<Hole>(h));
    append(out, "    #%-2zu  u %+7.3f  v %+7.3f m  r %.3f m  support %3zu  %s\n", i, q.x(), q.y(),
           r.candidates[i].radius,
           i < r.candidate_points.size() ? r.candidate_points[i] : std::size_t{0}, label.c_str());
  }
}

void describe_centers(std::string& out, const BranchReport& report, const char* frame_name) {
  if (!report.found) return;
  append(out, "  centres [m, %s]\n", frame_name);
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector3d& c = report.centers[h];
    append(out, "    %s  (%8.4f, %8.4f, %8.4f)\n", hole_name(static_cast<Hole>(h)), c.x(), c.y(), c.z());
  }
}

const char* placement_name(DiscontinuityFilter::EdgePlacement placement) {
  return placement == DiscontinuityFilter::EdgePlacement::Midpoint ? "midpoint"
                                                                   : "last board point";
}


void describe_stereo(std::string& out, const std::optional<StereoMatcher::Result>& result,
                     const StereoMatcher::Params& p, const StereoCamera& cameras, const char* name) {
  if (!result) return;
  const auto& s = *result;
  const std::size_t cells = s.disparity.values.size();
  const auto matched = std::count_if(s.disparity.values.begin(), s.disparity.values.end(),
                                     [](float d) { return std::isfinite(d); });
  append(out, "  %-16s %ld of %zu disparity cells matched (%.0f%%) -> %zu points; SGBM %.0f ms%s%s\n", name,
         static_cast<long>(matched), cells, cells ? 100.0 * matched / cells : 0.0, s.cloud.size(), s.match_ms,
         s.found ? "" : ": ", s.found ? "" : s.reason.c_str());
  append(out,
         "                   [stereo: working range %.2f..%.2f m; searched disparity %.1f..%.1f px on this rig "
         "(fx*B %.1f px m), %zu matches at the window's edge dropped, block_size %d, row_downscale %.2f]\n",
         p.min_depth, p.max_depth, s.min_disparity, s.max_disparity, cameras.left.fx() * cameras.baseline(),
         s.window_edge, p.block_size, p.row_downscale);
}

// The coarse pass of the board locator and the regions it chose.
void describe_located(std::string& out, const std::optional<StereoBoardLocator::Result>& located,
                      const StereoBoardLocator::Params& p) {
  if (!located) return;
  const auto& l = *located;
  append(out,
         "  coarse search    scale %.2f: %zu stereo points (SGBM %.0f ms), %zu after pass-through, "
         "%zu region(s) to match at full resolution%s%s\n",
         l.scale, l.stereo.cloud.size(), l.stereo.match_ms, l.cloud.size(), l.regions.size(),
         l.found ? "" : ": ", l.found ? "" : l.reason.c_str());
  for (const auto& r : l.regions)
    append(out, "    plane #%-2d      region x %d..%d, y %d..%d px, depth %.2f..%.2f m\n", r.candidate,
           r.roi.x, r.roi.x + r.roi.width - 1, r.roi.y, r.roi.y + r.roi.height - 1, r.min_depth, r.max_depth);
  append(out, "                   [locator: coarse_width %.0f px, min_board_px %.0f, coarse_stride %d, region_margin %.2f m, "
         "depth_margin %.2f m]\n", p.coarse_width, p.min_board_px, p.coarse_stride, p.region_margin, p.depth_margin);
}

void describe_edges(std::string& out, const std::optional<EdgeFilter::Result>& edges, const EdgeFilter::Params& p) {
  if (!edges) return;
  const auto& e = *edges;
  append(out,
         "  edges            %zu board points: %zu on image edges, %zu removed as %d border "
         "lines -> %zu edge points%s%s\n",
         e.input_points, e.edge_points, e.border_points, e.border_lines, e.edges.size(),
         e.found ? "" : ": ", e.found ? "" : e.reason.c_str());
  append(out,
         "                   [edges: sobel_threshold %.0f, magnitude %s, remove_border_lines %s, "
         "line_distance %.3f m, max_border_lines %d, min_line_points %d]\n",
         p.sobel_threshold, p.magnitude == EdgeFilter::Magnitude::Hypot ? "hypot" : "half-L1",
         yes_no(p.remove_border_lines), p.line_distance, p.max_border_lines, p.min_line_points);
}

// The rim refinement and the board pose the camera branch ended with.
void describe_refinement(std::string& out, const CameraInspection& in, const BoardPoseRefiner::Params& p) {
  if (in.refined) {
    const auto& r = *in.refined;
    if (r.converged)
      append(out, "  rim refinement   converged: rms %.2f px over %d samples, %d rounds%s\n",
             r.rms_px, r.samples, r.iterations,
             r.edges_from_board_side ? " (each rim's first edge from the board's face, not its strongest)" : "");
    else
      append(out, "  rim refinement   did not converge (%s): rms %.2f px, %d samples, %d rounds\n",
             r.reason.c_str(), r.rms_px, r.samples, r.iterations);
    append(out,
           "                   [board_refiner: search_range_px %.1f -> %.1f, edge strength %.1f "
           "(min_edge_strength %.1f, rim_contrast_fraction %.2f, edge_noise_factor %.1f), max_rms_px %.2f, "
           "min_samples %d]\n",
           p.search_range_px, p.final_search_range_px, r.edge_strength, p.min_edge_strength,
           p.rim_contrast_fraction, p.edge_noise_factor, p.max_rms_px, p.min_samples);
    if (r.outline_used)
      append(out,
             "  board outline    fitted with the rims: rms %.2f px over %d samples; its sides %+.1f mm and top "
             "and bottom %+.1f mm out of target.yaml's size, right view %+.2f px\n",
             r.outline_rms_px, r.outline_samples, 1e3 * r.outline_dilation.x(), 1e3 * r.outline_dilation.y(),
             r.outline_disparity_bias_px);
    else if (!r.outline_reason.empty())
      append(out, "  board outline    left out (%s); the pose is the rims' alone\n", r.outline_reason.c_str());
    const Eigen::Isometry3d& T = r.converged ? r.T_camera_board : *in.T_camera_board_initial;
    const Eigen::Vector3d t = T.translation();
    const Eigen::Vector3d z = T.linear().col(2);
    append(out, "  board pose       %s: centre (%.4f, %.4f, %.4f) m, normal (%.3f, %.3f, %.3f)\n",
           r.converged ? "refined" : "from the stereo circles", t.x(), t.y(), t.z(), z.x(), z.y(),
           z.z());
  } else if (in.circles && in.circles->found) {
    append(out,
           "  rim refinement   off (refine_camera_pose: false); centres from the stereo circles\n");
    if (in.T_camera_board_initial) {
      const Eigen::Vector3d t = in.T_camera_board_initial->translation();
      const Eigen::Vector3d z = in.T_camera_board_initial->linear().col(2);
      append(out,
             "  board pose       from the stereo circles: centre (%.4f, %.4f, %.4f) m, normal "
             "(%.3f, %.3f, %.3f)\n",
             t.x(), t.y(), t.z(), z.x(), z.y(), z.z());
    }
  }
}

}  // namespace

LidarInspection inspect_lidar(const LidarCloud& sweep, const Target& target,
                              const Calibrator::Params& params) {
  params.validate();
  target.validate();
  LidarInspection inspection;
  const auto start = std::chrono::steady_clock::now();
  inspection.report = detail::run_lidar_branch(sweep, target, params, &inspection);
  inspection.report.milliseconds = elapsed_ms(start);
  return inspection;
}

LidarInspection inspect_lidar(const std::vector<LidarCloud>& sweeps, const Target& target,
                              const Calibrator::Params& params) {
  params.validate();
  target.validate();
  std::vector<const LidarCloud*> window;
  for (const LidarCloud& sweep : sweeps) window.push_back(&sweep);
  LidarInspection inspection;
  const auto start = std::chrono::steady_clock::now();
  inspection.report = detail::run_ring_free_branch(detail::accumulate_ring_free(window, params), target, params,
                                                   &inspection);
  inspection.report.milliseconds = elapsed_ms(start);
  return inspection;
}

CameraInspection inspect_camera(const Image& left, const Image& right, const StereoCamera& cameras,
                                const Target& target, const Calibrator::Params& params) {
  params.validate();
  target.validate();
  detail::check_cameras(cameras);
  detail::check_stereo_images(left, right, cameras);
  CameraInspection inspection;
  const auto start = std::chrono::steady_clock::now();
  inspection.report = detail::run_camera_branch(left, right, detail::CameraSetup(cameras), target, params, &inspection);
  inspection.report.milliseconds = elapsed_ms(start);
  return inspection;
}

std::string describe(const LidarInspection& in, const Calibrator::Params& params) {
  std::string out;
  describe_status(out, "lidar", in.report);
  if (!in.path.empty()) append(out, "  path             %s [lidar_scan]\n", in.path.c_str());
  const std::size_t input =
      in.pass_through ? in.pass_through->kept.size() + in.pass_through->dropped_non_finite +
                            in.pass_through->dropped_box + in.pass_through->dropped_range
                      : 0;
  describe_pass_through(out, in.pass_through, input, params.lidar_pass_through,
                        "lidar_pass_through");
  describe_plane(out, in.plane, params.lidar_plane, "lidar_plane");
  describe_hypotheses(out, in.hypotheses, params.lidar_verifier, "lidar_verifier");
  if (in.candidate >= 0)
    append(out, "  (stages below ran on plane #%d, %s)\n", in.candidate,
           in.report.found ? "the chosen hypothesis" : "the most board-like one");

  if (in.discontinuities) {
    const auto& d = *in.discontinuities;
    const auto& c = d.counts;
    const auto& p = params.discontinuity;
    append(out,
           "  discontinuities  %zu rings cross the board (%zu board points): %zu hole crossings, %zu "
           "see-through gaps wider than a hole, %zu occlusions, %zu stray returns dropped;\n",
           c.rings, c.board_points, c.hole_crossings, c.wide_gaps, c.occlusions, c.stray_points);
    append(out, "                   rings kept %zu, rejected %zu (more than %d hole edges) -> %zu edge points%s%s\n",
           c.rings_kept, c.rings_rejected, p.max_ring_edges, d.edges.size(), d.found ? "" : ": ",
           d.found ? "" : d.reason.c_str());
    append(out,
           "                   [discontinuity: min_discontinuity %.2f m, max_stray_points %d, "
           "hole_gap_tolerance %.2f, max_ring_edges %d, placement %s]\n",
           p.min_discontinuity, p.max_stray_points, p.hole_gap_tolerance, p.max_ring_edges,
           placement_name(p.placement));
  }
  if (in.occupancy) {
    const auto& o = *in.occupancy;
    const auto& p = params.occupancy;
    append(out,
           "  occupancy        ring-free cloud: %zu board points in %.1f mm cells, %d hole(s) -> %zu rim points%s%s\n",
           o.board_points, o.cell * 1e3, o.holes, o.edges.size(), o.found ? "" : ": ",
           o.found ? "" : o.reason.c_str());
    append(out,
           "                   [occupancy: cell_factor %.1f, cell %.3f..%.3f m, min_hole_depth %.2f radii, "
           "rim_sectors %d; ring_free_frames %d]\n",
           p.cell_factor, p.min_cell, p.max_cell, p.min_hole_depth, p.rim_sectors,
           params.ring_free_frames);
  }
  if (in.circles && in.plane && in.candidate >= 0) {
    const PlaneCandidate& plane = in.plane->candidates[in.candidate];
    const Eigen::Vector3d centre = detail::centroid(in.cloud.points, plane.inliers);
    describe_circles(out, in.circles, plane.plane, Eigen::Vector3d::UnitZ(), centre,
                     params.lidar_circles, "lidar_circles", 1e3, "mm");
    if (in.circles->found)
      append(out, "  apparent holes   r %.1f mm%s\n", in.circles->radius * 1e3,
             params.lidar_circles.fit_radius ? " (fitted; lidars see holes smaller than they are)" : " (target's)");
  }
  describe_centers(out, in.report, "lidar frame");
  return out;
}

std::string describe(const CameraInspection& in, const Calibrator::Params& params,
                     const StereoCamera& cameras) {
  std::string out;
  describe_status(out, "camera", in.report);
  const Eigen::Vector3d up_optical(0.0, -1.0, 0.0);

  describe_located(out, in.located, params.locator);
  describe_stereo(out, in.stereo, params.stereo, cameras, in.located ? "region stereo" : "stereo");
  describe_pass_through(out, in.pass_through, in.stereo ? in.stereo->cloud.size() : 0,
                        params.camera_pass_through, "camera_pass_through");
  describe_plane(out, in.plane, in.located ? params.locator.plane : params.camera_plane,
                 in.located ? "locator.plane" : "camera_plane");
  describe_hypotheses(out, in.hypotheses, params.camera_verifier, "camera_verifier");
  if (in.candidate >= 0)
    append(out, "  (stages below ran on plane #%d, %s: %zu board-plane points at full resolution)\n",
           in.candidate, in.report.found ? "the chosen hypothesis" : "the most board-like one", in.board.size());

  describe_edges(out, in.edges, params.edges);
  if (in.circles) {
    const Eigen::Vector3d centre = detail::centroid(in.board.points, {});
    describe_circles(out, in.circles, in.board_plane, up_optical, centre, params.camera_circles,
                     "camera_circles", 1e3, "mm");
  }
  describe_refinement(out, in, params.board_refiner);
  if (!in.report.found && in.circles && in.circles->found) {
    // A later step rejected the frame: the circles' centres still tell where the holes are.
    BranchReport circles = in.report;
    circles.found = true;
    circles.centers = in.circles->centers;
    describe_centers(out, circles, "left camera optical frame; stereo circles, not used");
  }
  describe_centers(out, in.report, "left camera optical frame");
  return out;
}

}  // namespace l2s
