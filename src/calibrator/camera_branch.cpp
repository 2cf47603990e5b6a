#include "calibrator/branches.hpp"
#include "calibrator/camera_attempt.hpp"
#include "calibrator/marker_depth_agreement.hpp"

#include "camera/cv_image.hpp"
#include "camera/stereo_cloud_subset.hpp"
#include "detail/board_frame.hpp"
#include "plane/plane_fit.hpp"
#include "verify/hypothesis_search.hpp"
#include "verify/rim_steps.hpp"
#include "verify/stereo_evidence.hpp"

#include <cmath>
#include <memory>
#include <sstream>

namespace l2s::detail {
namespace {

const Eigen::Vector3d kUpOptical(0.0, -1.0, 0.0);

/// A refinement that ended far above its limit did not settle near any pose:
/// the circles' pose is not one the images' rims agree with (a non-converged
/// one that stopped on its round limit is usually still close, ~0.1 px).
/// On random scenes such frames were 8-40 cm off.
bool refinement_diverged(const BoardPoseRefiner::Result& refined, const BoardPoseRefiner::Params& params) {
  constexpr double kDivergedFactor = 5.0;
  return !refined.converged && refined.rms_px > kDivergedFactor * params.max_rms_px;
}

BranchReport fail(BranchReport report, const char* stage, const std::string& reason) {
  report.found = false;
  report.failed_stage = stage;
  report.reason = reason;
  return report;
}

/// The points of `cloud` within `band` of `plane` (or 3 sigma of their depth
/// noise, where larger), after refitting the plane to them twice (the first
/// slice leans towards the plane it was cut with).
StereoCloud board_points(const StereoCloud& cloud, double band, double depth_noise, Plane& plane) {
  std::vector<std::size_t> near;
  for (double factor : {2.0, 1.0, 1.0}) {
    near.clear();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const Eigen::Vector3d& p = cloud.points[i];
      if (std::abs(plane.signedDistance(p)) <= factor * std::max(band, 3.0 * depth_noise * p.squaredNorm()))
        near.push_back(i);
    }
    if (near.size() < 3) break;
    plane = facing_origin(fit_plane(cloud.points, near));
  }
  return subset(cloud, near);
}

/// Board points, edges, circles and the images' evidence for one hypothesis:
/// with a located board, from a full-resolution pass over its region; else
/// from the full-frame cloud's candidate. An attempt is shared, not copied,
/// between the search and what `l2s detect` shows (its region's cloud and
/// board points are megabytes).
class CameraHypothesisTester {
 public:
  CameraHypothesisTester(const CameraFrame& frame, const PlaneSegmenter::Result& planes,
                         const StereoBoardLocator::Result* located, const StereoCloud* full_cloud)
      : f_(frame), planes_(planes), located_(located), full_cloud_(full_cloud) {}

  std::optional<std::shared_ptr<CameraAttempt>> operator()(BoardHypothesis& hypothesis) {
    const auto shared = std::make_shared<CameraAttempt>();
    CameraAttempt& attempt = *shared;
    attempt.candidate = hypothesis.candidate;
    if (const int same = board_already_tried(attempt.candidate); same >= 0) {
      stop(hypothesis, "duplicate", "a piece of the board already found on plane #" + std::to_string(same));
      return std::nullopt;
    }
    if (!first_) first_ = shared;
    if (!(collect_board(attempt, hypothesis) && find_holes(attempt, hypothesis))) return std::nullopt;
    attempt.T_camera_board = board_pose_from_centers(attempt.circles.centers, attempt.plane);
    boards_found_.push_back({attempt.candidate, attempt.T_camera_board});
    StereoEvidenceParams evidence_params;
    evidence_params.max_depth = f_.params.stereo.max_depth;
    hypothesis.evidence = stereo_evidence(f_.left_gray, f_.right_gray, f_.cameras, attempt.T_camera_board,
                                          f_.target, f_.params.camera_verifier, evidence_params);
    hypothesis.evidence.fit_rms = attempt.circles.rms;
    hypothesis.evidence.fit_scale = 0.25 * f_.params.camera_circles.inlier_threshold;
    // The rim refinement is the sharpest test of a guess: a true board's rims
    // are edges in both images where the fit predicts them.
    if (f_.params.refine_camera_pose) {
      attempt.refined = BoardPoseRefiner(f_.params.board_refiner)
                            .refine(f_.left, f_.right, f_.cameras, f_.target, attempt.T_camera_board);
      hypothesis.evidence.rim_support = attempt.refined->edge_fraction;
      hypothesis.evidence.rim_background = attempt.refined->face_edge_fraction;
      if (refinement_diverged(*attempt.refined, f_.params.board_refiner)) {
        std::ostringstream reason;
        reason.precision(1);
        reason << std::fixed << "the rim refinement diverged (rms " << attempt.refined->rms_px
               << " px): no pose of this board fits the images' rims";
        stop(hypothesis, "refine", reason.str());
        return std::nullopt;
      }
      confirm_faint_rims(attempt.refined->T_camera_board, hypothesis.evidence);
      if (!attempt.refined->converged && !holes_plainly_open(hypothesis.evidence)) {
        stop(hypothesis, "refine",
             "the rim refinement did not converge (" + attempt.refined->reason +
                 ") and the images do not show all four holes open in a smooth face: nothing confirms the "
                 "circles' pose");
        return std::nullopt;
      }
    }
    return shared;
  }

  /// The first hypothesis tried: what `l2s detect` shows when none is
  /// verified, with the stage that rejected it.
  const std::shared_ptr<CameraAttempt>& first() const { return first_; }

 private:
  bool stop(BoardHypothesis& hypothesis, const char* stage, const std::string& reason) {
    hypothesis.stage = stage;
    hypothesis.reason = reason;
    return false;
  }

  /// Whether the images show every hole open (the stereo evidence inside it)
  /// in a face with few edges beside the rims: what still confirms a board
  /// whose rim refinement did not converge. Such boards were mostly
  /// something else: on 100 random scenes (frames 0, 5, 10) 17 of the 23
  /// accepted without a converged refinement were 4 cm to 3.4 m off (boxes,
  /// wall patches, the pattern one hole off), against 6 of the 244 with one;
  /// the three within 2 cm (two scenes) showed all four holes open beside a
  /// face with at most 2 % of its samples on an edge.
  bool holes_plainly_open(const BoardEvidence& e) const {
    constexpr double kSmoothFace = 0.1;  // rim_background: share of the face's samples (or arcs) with an edge
    const BoardVerifier::Params& v = f_.params.camera_verifier;
    for (int h = 0; h < 4; ++h) {
      const int samples = e.hole_open[h] + e.hole_blocked[h];
      if (samples < v.min_samples || e.hole_open[h] < v.min_hole_open * samples) return false;
    }
    return std::isfinite(e.rim_background) && e.rim_background <= kSmoothFace;
  }

  /// Rims too faint for an edge per sample (a gray board before a gray
  /// wall) are confirmed by their brightness step summed along arcs: where
  /// that tells the rims from the face around them better than the edges
  /// do, it is the rims' evidence. A low-contrast board before a plain wall
  /// of nearly its gray shows rims of 3-5 gray levels of step over 5 px:
  /// about one rim sample in five finds an edge, too few to keep the board,
  /// while the step summed along each arc stands well above the noise.
  void confirm_faint_rims(const Eigen::Isometry3d& T_camera_board, BoardEvidence& evidence) const {
    const RimSteps steps = rim_steps(f_.left_gray, f_.right_gray, f_.cameras, f_.target, T_camera_board);
    if (!(std::isfinite(steps.rims) && std::isfinite(steps.face))) return;
    const double edges = evidence.rim_support - evidence.rim_background;
    if (std::isfinite(edges) && edges >= steps.rims - steps.face) return;
    evidence.rim_support = steps.rims;
    evidence.rim_background = steps.face;
  }

  /// The candidate whose holes were already found on a board that this
  /// candidate's patch lies on (same place, same facing), or -1. The coarse
  /// pass often cuts one board into several patches; each would cost a
  /// region's full-resolution matching and every later stage, and end on the
  /// same board.
  int board_already_tried(int candidate) const {
    if (boards_found_.empty()) return -1;
    const PlaneCandidate& patch = planes_.candidates[candidate];
    const StereoCloud& cloud = located_ ? located_->cloud : *full_cloud_;
    if (patch.inliers.empty()) return -1;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (std::size_t i : patch.inliers) centroid += cloud.points[i];
    centroid /= static_cast<double>(patch.inliers.size());
    const double max_tilt = std::cos(20.0 * M_PI / 180.0);
    const double depth_band = std::max(0.05, 2.0 * f_.params.camera_plane.inlier_threshold);
    for (const auto& [tried, T_camera_board] : boards_found_) {
      const Eigen::Vector3d on_board = T_camera_board.inverse() * centroid;
      const bool inside = std::abs(on_board.x()) <= 0.5 * f_.target.board_width &&
                          std::abs(on_board.y()) <= 0.5 * f_.target.board_height &&
                          std::abs(on_board.z()) <= depth_band;
      const bool facing = std::abs(patch.plane.normal().dot(T_camera_board.linear().col(2))) >= max_tilt;
      if (inside && facing) return tried;
    }
    return -1;
  }

  bool collect_board(CameraAttempt& attempt, BoardHypothesis& hypothesis) {
    const PlaneCandidate& candidate = planes_.candidates[attempt.candidate];
    attempt.plane = candidate.plane;
    if (!located_) {
      attempt.board = subset(*full_cloud_, candidate.inliers);
      return true;
    }
    const auto region = std::find_if(located_->regions.begin(), located_->regions.end(),
                                     [&](const auto& r) { return r.candidate == attempt.candidate; });
    StereoMatcher::Params fine = f_.params.stereo;
    fine.roi = region->roi;
    fine.min_depth = std::max(fine.min_depth, region->min_depth);
    fine.max_depth = std::min(fine.max_depth, region->max_depth);
    attempt.stereo = StereoMatcher(fine).match(f_.left, f_.right, f_.cameras);
    if (!attempt.stereo->found) return stop(hypothesis, "stereo", "region: " + attempt.stereo->reason);
    const StereoCloud& cloud = attempt.stereo->cloud;
    const auto kept = PassThroughFilter(f_.params.camera_pass_through).filter(cloud.points);
    if (candidate.oversized) return board_in_region(attempt, hypothesis, subset(cloud, kept.kept));
    attempt.board = board_points(subset(cloud, kept.kept), f_.params.camera_plane.inlier_threshold,
                                 attempt.stereo->depth_noise, attempt.plane);
    if (attempt.board.size() < 3) return stop(hypothesis, "plane", "no board-plane points at full resolution");
    return true;
  }

  /// A coarse patch larger than the board (the board merged with what
  /// touches it in coarse depth): the board is looked for again among the
  /// planes of its region's full-resolution cloud.
  bool board_in_region(CameraAttempt& attempt, BoardHypothesis& hypothesis, const StereoCloud& region) {
    PlaneSegmenter::Params params = f_.params.camera_plane;
    params.depth_noise = attempt.stereo->depth_noise;
    params.keep_oversized = false;
    const PlaneSegmenter::Result planes = PlaneSegmenter(params).segment(region.points, f_.target);
    if (!planes.found) return stop(hypothesis, "plane", "oversized patch, region at full resolution: " + planes.reason);
    attempt.plane = planes.plane;
    attempt.board = subset(region, planes.inliers);
    return true;
  }

  /// Edges and circles; on a colour image whose gray edges show no hole
  /// pattern, once more with colour edges (rims that differ from the face in
  /// hue more than in brightness).
  bool find_holes(CameraAttempt& attempt, BoardHypothesis& hypothesis) {
    if (find_holes_with(f_.params.edges, attempt, hypothesis)) return true;
    if (f_.left.channels != 3 || f_.params.edges.colour) return false;
    auto gray_edges = std::move(attempt.edges);
    auto gray_circles = std::move(attempt.circles);
    const std::string stage = hypothesis.stage, reason = hypothesis.reason;
    EdgeFilter::Params colour = f_.params.edges;
    colour.colour = true;
    if (find_holes_with(colour, attempt, hypothesis)) return true;
    // `l2s detect` shows the gray try, the ordinary one.
    attempt.edges = std::move(gray_edges);
    attempt.circles = std::move(gray_circles);
    hypothesis.stage = stage;
    hypothesis.reason = reason + " (nor with colour edges)";
    return false;
  }

  bool find_holes_with(const EdgeFilter::Params& edge_params, CameraAttempt& attempt, BoardHypothesis& hypothesis) {
    hypothesis.stage.clear();
    attempt.edges = EdgeFilter(edge_params).filter(f_.left, f_.cameras.left, attempt.board, attempt.plane, f_.target);
    if (!attempt.edges.found) return stop(hypothesis, "edges", attempt.edges.reason);
    attempt.circles = CircleFinder(f_.params.camera_circles)
                          .find(attempt.edges.edges.points, attempt.plane, kUpOptical, f_.target,
                                attempt.edges.gradients);
    if (!attempt.circles.found) return stop(hypothesis, "circles", attempt.circles.reason);
    return true;
  }

  const CameraFrame& f_;
  const PlaneSegmenter::Result& planes_;
  const StereoBoardLocator::Result* located_;
  const StereoCloud* full_cloud_;
  std::shared_ptr<CameraAttempt> first_;
  std::vector<std::pair<int, Eigen::Isometry3d>> boards_found_;  ///< (candidate, T_camera_board) with four holes
};

/// Moves what `l2s detect` shows of the attempt into the trace (the region's
/// cloud and board points are megabytes; the attempt is not needed after).
void keep_stages(CameraInspection& t, CameraAttempt&& attempt) {
  t.candidate = attempt.candidate;
  if (attempt.stereo) t.stereo = std::move(attempt.stereo);
  t.board = std::move(attempt.board);
  t.board_plane = attempt.plane;
  if (!t.board.points.empty()) t.edges = std::move(attempt.edges);
  if (t.edges && t.edges->found) t.circles = std::move(attempt.circles);
  if (t.circles && t.circles->found) t.T_camera_board_initial = attempt.T_camera_board;
  t.refined = std::move(attempt.refined);
}

/// The candidates of the frame: located at low resolution, or segmented in
/// one full-frame cloud. Empty optional and a failed report when none.
const PlaneSegmenter::Result* find_candidates(const CameraFrame& f, CameraInspection& t, BranchReport& report) {
  if (f.params.locate_board) {
    const auto& located = t.located.emplace(StereoBoardLocator(f.params.locator)
                                                .locate(f.left, f.right, f.cameras, f.target, f.params.stereo,
                                                        f.params.camera_pass_through));
    report.input_points = located.cloud.size();
    if (!located.found) {
      report = fail(report, located.stereo.found ? "plane" : "stereo", located.reason);
      return nullptr;
    }
    return &t.plane.emplace(located.plane);
  }
  const auto& stereo = t.stereo.emplace(StereoMatcher(f.params.stereo).match(f.left, f.right, f.cameras));
  if (!stereo.found) {
    report = fail(report, "stereo", stereo.reason);
    return nullptr;
  }
  const auto& kept = t.pass_through.emplace(PassThroughFilter(f.params.camera_pass_through).filter(stereo.cloud.points));
  t.cloud = subset(stereo.cloud, kept.kept);
  report.input_points = t.cloud.size();
  if (t.cloud.size() < 3) {
    report = fail(report, "pass_through", "no stereo points inside the pass-through limits");
    return nullptr;
  }
  PlaneSegmenter::Params plane = f.params.camera_plane;
  plane.depth_noise = stereo.depth_noise;
  const auto& planes = t.plane.emplace(PlaneSegmenter(plane).segment(t.cloud.points, f.target));
  if (!planes.found) {
    report = fail(report, "plane", planes.reason);
    return nullptr;
  }
  return &planes;
}

/// The default preset's last step: the centres from the board pose fitted to
/// the hole rims in both images. A frame whose refinement fails keeps the
/// stereo circles (rim_rms_px stays 0): a pose made of such frames only still
/// gets a result, and a pose with enough refined frames leaves them out
/// (pose_registration.cpp).
void take_refined_centres(const CameraAttempt& attempt, BranchReport& report) {
  if (!attempt.refined) return;
  if (attempt.refined->converged) {
    report.centers = attempt.refined->centers;
    report.rim_rms_px = attempt.refined->rms_px;
    if (!attempt.refined->outline_reason.empty())
      report.note = "board outline left out (" + attempt.refined->outline_reason + "); the rims alone kept";
  } else {
    report.note = "rim refinement did not converge (" + attempt.refined->reason + "); stereo circles kept";
  }
}

/// The hole centres of a board the stereo search found: on its rims where
/// their refinement converged, else the stereo circles'.
HoleCenters stereo_centres(const CameraAttempt& attempt) {
  return attempt.refined && attempt.refined->converged ? attempt.refined->centers : attempt.circles.centers;
}

/// The hole centres of a board its markers gave: on its rims where their
/// refinement converged (board_from_markers keeps no other), else where the
/// markers' pose puts them.
HoleCenters marker_centres(const CameraAttempt& attempt, const Target& target) {
  return attempt.refined ? attempt.refined->centers : hole_centres_at(target, attempt.T_camera_board);
}

void take_stereo_board(CameraAttempt&& board, BranchReport& report, CameraInspection& t) {
  report.plane_inliers = board.board.size();
  report.edge_points = board.edges.edges.size();
  report.fit_rms = board.circles.rms;
  report.hole_radius = board.circles.radius;
  report.centers = board.circles.centers;
  report.found = true;
  take_refined_centres(board, report);
  keep_stages(t, std::move(board));
}

void take_marker_board(CameraAttempt&& board, const Target& target, BranchReport& report, CameraInspection& t) {
  report.found = true;
  report.hole_radius = target.hole_radius;
  report.centers = marker_centres(board, target);
  report.rim_rms_px = board.refined ? board.refined->rms_px : 0.0;
  report.markers = board.markers;
  t.T_camera_board_initial = board.T_camera_board;
  t.refined = std::move(board.refined);
}

/// A board the stereo search did not find, or found elsewhere: its pair's
/// disparity is not one the calibration check may measure the board's depth
/// by (on a plain wall or through a short baseline it tilted 14-21 deg).
void drop_stereo_depth(CameraInspection& t) {
  t.located.reset();
  t.stereo.reset();
}

/// Both the markers and the stereo search found a board. Where they put its
/// holes within half a hole radius of each other they found the same board:
/// its pose is the markers' unless only the stereo board's rims converged
/// (a rim fit is sharper than corners), and the pair's depth stays evidence
/// for the check. Farther apart, the stereo search took something else for
/// the board (a patch of its face, a pattern one hole off): the markers'
/// ids tie them to the target, and they win.
void choose_between(CameraAttempt&& stereo, CameraAttempt&& marked, const std::string& marker_how,
                    const Target& target, BranchReport& report, CameraInspection& t) {
  const HoleCenters by_stereo = stereo_centres(stereo), by_markers = marker_centres(marked, target);
  double apart = 0.0;
  for (std::size_t h = 0; h < 4; ++h) apart = std::max(apart, (by_stereo[h] - by_markers[h]).norm());
  std::ostringstream text;
  text.precision(0);
  text << std::fixed << "markers (" << marker_how << ") and the stereo board " << (apart * 1e3)
       << " mm apart at most: ";
  // The same board: the stereo stages stay what `l2s detect` shows.
  const bool same_board = apart <= 0.5 * target.hole_radius;
  const bool stereo_pose = same_board && stereo.refined && stereo.refined->converged && !marked.refined;
  if (same_board)
    take_stereo_board(std::move(stereo), report, t);
  else
    drop_stereo_depth(t);
  if (stereo_pose) {
    report.markers = marked.markers;  // the same holes, labelled alike
    report.note = text.str() + "the same board; the stereo board's pose kept, its rims converged";
    return;
  }
  take_marker_board(std::move(marked), target, report, t);
  report.note = text.str() + (same_board ? "the same board; the markers' pose kept"
                                         : "not the same board; the markers won, their ids tie them to the target");
}

/// The board's pose from its markers, refined on its rims in both images
/// and verified there: the stereo search would only find the same board
/// again or lose to the markers' ids, so the pair is matched only at the
/// coarse scale, for the calibration check's depth of the whole scene. That
/// depth stays evidence only where it shows the board where the markers do
/// (a plain face or wall, or a short baseline, can tilt it by degrees).
void take_board_of_markers_alone(CameraAttempt&& marked, const std::string& marker_how, const CameraFrame& f,
                                 BranchReport& report, CameraInspection& t) {
  const Eigen::Isometry3d T_camera_board = marked.refined->T_camera_board;
  take_marker_board(std::move(marked), f.target, report, t);
  report.note = "the markers gave the pose, refined on the rims (" + marker_how + "); no stereo search";
  auto& coarse = t.located.emplace(StereoBoardLocator(f.params.locator)
                                       .match_coarse(f.left, f.right, f.cameras, f.target, f.params.stereo,
                                                     f.params.camera_pass_through));
  if (!coarse.stereo.found) {
    drop_stereo_depth(t);
    return;
  }
  const MarkerDepthAgreement agreement = marker_depth_agreement(coarse.cloud, T_camera_board, f.target);
  coarse.reason = "no regions searched: the markers located the board";
  report.note += "; " + agreement.summary + (agreement.agrees ? ": kept for the check" : ": not the check's evidence");
  if (!agreement.agrees) drop_stereo_depth(t);
}

/// The board looked for in the stereo cloud (candidate planes, each verified
/// in turn), beside the markers' pose when they gave one that their rims did
/// not confirm.
void search_stereo_cloud(const CameraFrame& f, std::optional<CameraAttempt> marked, const std::string& marker_how,
                         BranchReport& report, CameraInspection& t) {
  const Target& target = f.target;
  const PlaneSegmenter::Result* planes = find_candidates(f, t, report);
  std::optional<std::shared_ptr<CameraAttempt>> found;
  if (planes) {
    CameraHypothesisTester tester(f, *planes, t.located ? &*t.located : nullptr, &t.cloud);
    found = search_hypotheses<std::shared_ptr<CameraAttempt>>(*planes, BoardVerifier(f.params.camera_verifier),
                                                              t.hypotheses, tester);
    report.hypotheses = static_cast<int>(t.hypotheses.size());
    if (!found) {
      if (tester.first()) keep_stages(t, std::move(*tester.first()));
      report = fail(report, t.hypotheses.front().stage.c_str(), describe_failed_search(t.hypotheses));
    }
  }
  if (found && marked) {
    choose_between(std::move(**found), std::move(*marked), marker_how, target, report, t);
  } else if (found) {
    take_stereo_board(std::move(**found), report, t);
    if (!marker_how.empty()) report.note += (report.note.empty() ? "" : "; ") + ("markers: " + marker_how);
  } else if (marked) {
    report.failed_stage.clear();
    report.reason.clear();
    take_marker_board(std::move(*marked), target, report, t);
    report.note = "no board in the stereo cloud; its markers gave the pose (" + marker_how + ")";
    drop_stereo_depth(t);
  } else {
    if (!marker_how.empty()) report.reason += "; markers: " + marker_how;
  }
}

}  // namespace

CameraSetup::CameraSetup(const StereoCamera& given) : cameras(given) {
  if (given.images != ImageKind::Raw) return;
  rectifier = std::make_shared<const StereoRectifier>(given);
  cameras = rectifier->rectified();
}

BranchReport run_camera_branch(const Image& raw_left, const Image& raw_right, const CameraSetup& setup,
                               const Target& target, const Calibrator::Params& params,
                               CameraInspection* trace) {
  CameraInspection local;
  CameraInspection& t = trace ? *trace : local;
  BranchReport report;
  if (setup.rectifier) {
    RectifiedPair pair = setup.rectifier->rectify(raw_left, raw_right);
    t.rectified = RectifiedView{std::move(pair.left), std::move(pair.right), setup.cameras,
                                setup.rectifier->R_rect_camera()};
  }
  const Image& left = t.rectified ? t.rectified->left : raw_left;
  const Image& right = t.rectified ? t.rectified->right : raw_right;
  const StereoCamera& cameras = setup.cameras;
  const CameraFrame frame{left, right, gray_mat(left, "left"), gray_mat(right, "right"), cameras, target, params};
  // Markers first: their ids tie their corners to the target, so the pose
  // they give in both images is the board's wherever the images show them.
  std::optional<CameraAttempt> marked;
  std::string marker_how;
  if (target.markers && params.board_from_markers) marked = board_from_markers(frame, marker_how);
  if (marked && marked->refined) {
    take_board_of_markers_alone(std::move(*marked), marker_how, frame, report, t);
  } else {
    search_stereo_cloud(frame, std::move(marked), marker_how, report, t);
  }
  if (!report.found) return report;
  if (setup.rectifier) {
    const Eigen::Isometry3d T_camera_rect = setup.rectifier->T_rect_camera().inverse();
    for (Eigen::Vector3d& c : report.centers) c = T_camera_rect * c;
  }
  return report;
}

}  // namespace l2s::detail
