#include "calibrator/branches.hpp"

#include <l2s/io/ring_recovery.hpp>

#include <algorithm>
#include <optional>

#include "detail/board_frame.hpp"
#include "plane/plane_fit.hpp"
#include "verify/cloud_evidence.hpp"
#include "verify/hypothesis_search.hpp"

namespace l2s::detail {
namespace {

BranchReport fail(BranchReport report, const char* stage, const std::string& reason) {
  report.found = false;
  report.failed_stage = stage;
  report.reason = reason;
  return report;
}

/// The stages run on one board hypothesis; `edges` or `occupancy` by the cloud's kind.
struct LidarAttempt {
  int candidate = -1;
  DiscontinuityFilter::Result edges;
  OccupancyEdgeFilter::Result occupancy;
  CircleFinder::Result circles;
};

/// Hole edges (ring discontinuities, or the occupancy of a ring-free cloud)
/// and circles on one plane candidate, and the evidence for the verifier.
class LidarHypothesisTester {
 public:
  LidarHypothesisTester(const LidarCloud& cloud, bool ring_free, const PlaneSegmenter::Result& planes,
                        const Target& target, const Calibrator::Params& params)
      : cloud_(cloud),
        ring_free_(ring_free),
        planes_(planes),
        target_(target),
        params_(params),
        discontinuity_(params.discontinuity),
        occupancy_(params.occupancy),
        circles_(params.lidar_circles) {}

  std::optional<LidarAttempt> operator()(BoardHypothesis& hypothesis) {
    const PlaneCandidate& plane = planes_.candidates[hypothesis.candidate];
    LidarAttempt attempt;
    attempt.candidate = hypothesis.candidate;
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    bool found = false;
    std::string reason;
    if (ring_free_) {
      attempt.occupancy = occupancy_.filter(cloud_.points, plane.plane, plane.inliers, up, target_);
      found = attempt.occupancy.found;
      reason = attempt.occupancy.reason;
      if (found) attempt.circles = circles_.find(attempt.occupancy.edges, plane.plane, up, target_);
    } else {
      attempt.edges = discontinuity_.filter(cloud_, plane.plane, plane.inliers, target_);
      found = attempt.edges.found;
      reason = attempt.edges.reason;
      if (found) attempt.circles = circles_.find(attempt.edges.edges, plane.plane, up, target_);
    }
    if (!first_) first_ = attempt;
    if (!found) {
      hypothesis.stage = ring_free_ ? "occupancy" : "discontinuities";
      hypothesis.reason = reason;
      return std::nullopt;
    }
    if (!attempt.circles.found) {
      hypothesis.stage = "circles";
      hypothesis.reason = attempt.circles.reason;
      if (ring_free_) {
        const std::string hint = attempt.occupancy.cut_board_hint(target_);
        if (!hint.empty()) hypothesis.reason += "; " + hint;
      }
      return std::nullopt;
    }
    // A ring-free window covers the board all over: a hole with open space
    // behind shows by the returns it lacks.
    const CloudEvidenceParams evidence{params_.lidar_plane.inlier_threshold, params_.discontinuity.min_discontinuity,
                                       ring_free_};
    hypothesis.evidence = cloud_evidence(cloud_.points, plane.plane,
                                         board_pose_from_centers(attempt.circles.centers, plane.plane), target_,
                                         params_.lidar_verifier, evidence);
    hypothesis.evidence.fit_rms = attempt.circles.rms;
    hypothesis.evidence.fit_scale = 0.25 * params_.lidar_circles.inlier_threshold;
    return attempt;
  }

  /// The first hypothesis tried (the most board-like plane), for diagnostics.
  const std::optional<LidarAttempt>& first() const { return first_; }

 private:
  const LidarCloud& cloud_;
  bool ring_free_;
  const PlaneSegmenter::Result& planes_;
  const Target& target_;
  const Calibrator::Params& params_;
  DiscontinuityFilter discontinuity_;
  OccupancyEdgeFilter occupancy_;
  CircleFinder circles_;
  std::optional<LidarAttempt> first_;
};

void keep_stages(LidarInspection& t, const LidarAttempt& attempt) {
  t.candidate = attempt.candidate;
  if (t.ring_free)
    t.occupancy = attempt.occupancy;
  else
    t.discontinuities = attempt.edges;
  if (attempt.edges.found || attempt.occupancy.found) t.circles = attempt.circles;
}

/// The plane search of this cloud. A ring-free lidar's field of view has a
/// hard outline (the Avia's ellipse, the Mid-360's lowest 7 deg) that can cut
/// the board, and its dense cloud still shows every hole that is in view: its
/// board candidates need only be long enough to hold the hole pattern with
/// half a radius of rim beyond it. The holes then verify the candidate.
PlaneSegmenter::Params plane_params(const Calibrator::Params& params, bool ring_free, const Target& target) {
  PlaneSegmenter::Params plane = params.lidar_plane;
  if (!ring_free) return plane;
  const bool wide = target.board_width >= target.board_height;
  const double spacing = wide ? target.hole_spacing_x : target.hole_spacing_y;
  const double pattern = spacing + 3.0 * target.hole_radius;
  plane.min_length_fraction =
      std::min(plane.min_length_fraction, pattern / std::max(target.board_width, target.board_height));
  return plane;
}

/// The hypotheses on the planes of `t.plane`, most board-like first; the
/// best verified one, or none. Fills `t.hypotheses` and, when none is
/// verified, the stages of the first tried.
std::optional<LidarAttempt> search_board(const LidarCloud& cloud, LidarInspection& t, const Target& target,
                                         const Calibrator::Params& params) {
  LidarHypothesisTester tester(cloud, t.ring_free, *t.plane, target, params);
  std::optional<LidarAttempt> best =
      search_hypotheses<LidarAttempt>(*t.plane, BoardVerifier(params.lidar_verifier), t.hypotheses, tester);
  if (!best && tester.first()) keep_stages(t, *tester.first());
  return best;
}

/// The branch on `sweep`; `ring_free` when the caller knows the cloud has no
/// ring structure (a window of ring-free sweeps), else it is classified here.
BranchReport run_branch(const LidarCloud& sweep, const Target& target, const Calibrator::Params& params,
                        LidarInspection* trace, bool known_ring_free) {
  LidarInspection local;
  LidarInspection& t = trace ? *trace : local;
  BranchReport report{};
  if (sweep.empty()) return fail(report, "input", "empty sweep");
  if (sweep.has_ring() && sweep.ring.size() != sweep.size())
    return fail(report, "input", "ring field has a different length than the points");
  if (sweep.has_intensity() && sweep.intensity.size() != sweep.size())
    return fail(report, "input", "intensity field has a different length than the points");

  const auto& kept =
      t.pass_through.emplace(PassThroughFilter(params.lidar_pass_through).filter(sweep.points));
  LidarCloud& cloud = t.cloud = select(sweep, kept.kept);
  report.input_points = cloud.size();
  if (cloud.size() < 3)
    return fail(report, "pass_through", "no finite points inside the pass-through limits");
  // The path is chosen after filtering: the board's rings are what matters,
  // and fewer points cluster faster. A ring field that does not give the
  // scan lines (a solid-state lidar's line number, a constant) is dropped and
  // the rings, if any, are recovered from the returns.
  if (known_ring_free) {
    t.ring_free = true;
    t.path = "ring-free: the sweeps of a window accumulated";
    cloud.ring.clear();
  } else {
    const SweepPath path = choose_path(cloud, params);
    t.ring_free = path.ring_free;
    t.path = path.reason;
    if (!path.use_field) cloud.ring.clear();
    if (!t.ring_free && !cloud.has_ring()) io::recover_rings(cloud);
  }

  const PlaneSegmenter::Params plane_search = plane_params(params, t.ring_free, target);
  t.plane = PlaneSegmenter(plane_search).segment(cloud.points, target);
  if (!t.plane->found) return fail(report, "plane", t.plane->reason);
  std::optional<LidarAttempt> best = search_board(cloud, t, target, params);
  std::string second_look;
  if (!best && t.ring_free) {
    // Seconds of a dense scan cover the floor: where the board's plane meets
    // it, a strip of floor returns lies within the plane's inlier distance
    // and joins the board through its stand into a patch larger than the
    // board. A second look without level surfaces (as for a stereo cloud)
    // sees the board on its own; its draws differ, so a board the first
    // look's candidates missed among many walls gets another chance.
    LidarInspection again;
    again.ring_free = true;
    PlaneSegmenter::Params without_level = plane_search;
    without_level.remove_level_planes = std::max(without_level.remove_level_planes, 2);
    again.plane = PlaneSegmenter(without_level).segment(cloud.points, target);
    if (again.plane->found) best = search_board(cloud, again, target, params);
    if (best) {
      t.plane = std::move(again.plane);
      t.hypotheses = std::move(again.hypotheses);
    } else if (!again.hypotheses.empty()) {
      second_look = "; again without level surfaces: " + describe_failed_search(again.hypotheses);
    }
  }
  const PlaneSegmenter::Result& planes = *t.plane;
  report.hypotheses = static_cast<int>(t.hypotheses.size());
  if (!best) {
    report.plane_inliers = planes.inliers.size();
    return fail(report, t.hypotheses.front().stage.c_str(), describe_failed_search(t.hypotheses) + second_look);
  }
  keep_stages(t, *best);
  report.plane_inliers = planes.candidates[best->candidate].inliers.size();
  report.edge_points = t.ring_free ? best->occupancy.edges.size() : best->edges.edges.size();
  report.fit_rms = best->circles.rms;
  report.hole_radius = best->circles.radius;
  report.found = true;
  report.centers = best->circles.centers;
  report.board_plane = facing_origin(planes.candidates[best->candidate].plane);
  if (!t.ring_free) report.rim_crossings = best->edges.crossings;
  return report;
}

}  // namespace

BranchReport run_lidar_branch(const LidarCloud& sweep, const Target& target, const Calibrator::Params& params,
                              LidarInspection* trace) {
  return run_branch(sweep, target, params, trace, false);
}

BranchReport run_ring_free_branch(const LidarCloud& window, const Target& target, const Calibrator::Params& params,
                                  LidarInspection* trace) {
  return run_branch(window, target, params, trace, true);
}

bool is_ring_free(const LidarCloud& sweep, const Calibrator::Params& params) {
  if (sweep.size() < 3) return false;
  if (sweep.has_ring() && sweep.ring.size() != sweep.size()) return false;
  if (sweep.has_intensity() && sweep.intensity.size() != sweep.size()) return false;
  return choose_path(sweep, params).ring_free;
}

LidarCloud accumulate_ring_free(const std::vector<const LidarCloud*>& sweeps, const Calibrator::Params& params) {
  LidarCloud cloud;
  const PassThroughFilter pass_through(params.lidar_pass_through);
  for (const LidarCloud* sweep : sweeps)
    for (const std::size_t i : pass_through.filter(sweep->points).kept) cloud.points.push_back(sweep->points[i]);
  return cloud;
}

}  // namespace l2s::detail
