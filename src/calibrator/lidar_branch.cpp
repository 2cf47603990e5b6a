#include "calibrator/branches.hpp"

#include <l2s/io/ring_recovery.hpp>

#include "detail/board_frame.hpp"
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

/// The stages run on one board hypothesis.
struct LidarAttempt {
  int candidate = -1;
  DiscontinuityFilter::Result edges;
  CircleFinder::Result circles;
};

/// Discontinuities and circles on one plane candidate, and the evidence for the verifier.
class LidarHypothesisTester {
 public:
  LidarHypothesisTester(const LidarCloud& cloud, const PlaneSegmenter::Result& planes, const Target& target,
                        const Calibrator::Params& params)
      : cloud_(cloud),
        planes_(planes),
        target_(target),
        params_(params),
        discontinuity_(params.discontinuity),
        circles_(params.lidar_circles) {}

  std::optional<LidarAttempt> operator()(BoardHypothesis& hypothesis) {
    const PlaneCandidate& plane = planes_.candidates[hypothesis.candidate];
    LidarAttempt attempt;
    attempt.candidate = hypothesis.candidate;
    attempt.edges = discontinuity_.filter(cloud_, plane.plane, plane.inliers, target_);
    if (attempt.edges.found)
      attempt.circles = circles_.find(attempt.edges.edges, plane.plane, Eigen::Vector3d::UnitZ(), target_);
    if (!first_) first_ = attempt;
    if (!attempt.edges.found) {
      hypothesis.stage = "discontinuities";
      hypothesis.reason = attempt.edges.reason;
      return std::nullopt;
    }
    if (!attempt.circles.found) {
      hypothesis.stage = "circles";
      hypothesis.reason = attempt.circles.reason;
      return std::nullopt;
    }
    const CloudEvidenceParams evidence{params_.lidar_plane.inlier_threshold, params_.discontinuity.min_discontinuity};
    hypothesis.evidence = cloud_evidence(cloud_.points, plane.plane,
                                         board_pose_from_centers(attempt.circles.centers, plane.plane), target_,
                                         params_.lidar_verifier, evidence);
    hypothesis.evidence.fit_rms = attempt.circles.rms;
    hypothesis.evidence.fit_scale = params_.lidar_circles.inlier_threshold;
    return attempt;
  }

  /// The first hypothesis tried (the most board-like plane), for diagnostics.
  const std::optional<LidarAttempt>& first() const { return first_; }

 private:
  const LidarCloud& cloud_;
  const PlaneSegmenter::Result& planes_;
  const Target& target_;
  const Calibrator::Params& params_;
  DiscontinuityFilter discontinuity_;
  CircleFinder circles_;
  std::optional<LidarAttempt> first_;
};

void keep_stages(LidarInspection& t, const LidarAttempt& attempt) {
  t.candidate = attempt.candidate;
  t.discontinuities = attempt.edges;
  if (attempt.edges.found) t.circles = attempt.circles;
}

}  // namespace

BranchReport run_lidar_branch(const LidarCloud& sweep, const Target& target, const Calibrator::Params& params,
                              LidarInspection* trace) {
  LidarInspection local;
  LidarInspection& t = trace ? *trace : local;
  BranchReport report;
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
  // Rings are recovered after filtering: the board's rings are what matters, and
  // fewer points cluster faster.
  if (!cloud.has_ring()) io::recover_rings(cloud);

  const auto& planes = t.plane.emplace(PlaneSegmenter(params.lidar_plane).segment(cloud.points, target));
  if (!planes.found) return fail(report, "plane", planes.reason);

  LidarHypothesisTester tester(cloud, planes, target, params);
  const std::optional<LidarAttempt> best =
      search_hypotheses<LidarAttempt>(planes, BoardVerifier(params.lidar_verifier), t.hypotheses, tester);
  report.hypotheses = static_cast<int>(t.hypotheses.size());
  if (!best) {
    if (tester.first()) keep_stages(t, *tester.first());
    report.plane_inliers = planes.inliers.size();
    return fail(report, t.hypotheses.front().stage.c_str(), describe_failed_search(t.hypotheses));
  }
  keep_stages(t, *best);
  report.plane_inliers = planes.candidates[best->candidate].inliers.size();
  report.edge_points = best->edges.edges.size();
  report.fit_rms = best->circles.rms;
  report.hole_radius = best->circles.radius;
  report.found = true;
  report.centers = best->circles.centers;
  return report;
}

}  // namespace l2s::detail
