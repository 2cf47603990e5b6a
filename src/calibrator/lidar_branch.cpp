#include "calibrator/branches.hpp"

#include <l2s/io/ring_recovery.hpp>

#include <chrono>

namespace l2s::detail {
namespace {

BranchReport fail(BranchReport report, const char* stage, const std::string& reason) {
  report.found = false;
  report.failed_stage = stage;
  report.reason = reason;
  return report;
}

}  // namespace

BranchReport run_lidar_branch(const LidarCloud& sweep, const Target& target,
                              const Calibrator::Params& params, LidarInspection* trace) {
  LidarInspection local;
  LidarInspection& t = trace ? *trace : local;
  BranchReport report;
  if (sweep.empty()) return fail(report, "input", "empty sweep");
  if (sweep.has_ring() && sweep.ring.size() != sweep.size())
    return fail(report, "input", "ring field has a different length than the points");

  const auto& kept =
      t.pass_through.emplace(PassThroughFilter(params.lidar_pass_through).filter(sweep.points));
  LidarCloud& cloud = t.cloud = select(sweep, kept.kept);
  report.input_points = cloud.size();
  if (cloud.size() < 3)
    return fail(report, "pass_through", "no finite points inside the pass-through limits");
  // Rings are recovered after filtering: the board's rings are what matters, and
  // fewer points cluster faster.
  if (!cloud.has_ring()) io::recover_rings(cloud);

  const auto& plane =
      t.plane.emplace(PlaneSegmenter(params.lidar_plane).segment(cloud.points, target));
  report.plane_inliers = plane.inliers.size();
  if (!plane.found) return fail(report, "plane", plane.reason);

  const auto& edges = t.discontinuities.emplace(
      DiscontinuityFilter(params.discontinuity).filter(cloud, plane.plane, plane.inliers));
  report.edge_points = edges.edges.size();
  if (!edges.found) return fail(report, "discontinuities", edges.reason);

  const auto& circles =
      t.circles.emplace(CircleFinder(params.lidar_circles)
                            .find(edges.edges, plane.plane, Eigen::Vector3d::UnitZ(), target));
  report.fit_rms = circles.rms;
  if (!circles.found) return fail(report, "circles", circles.reason);

  report.found = true;
  report.centers = circles.centers;
  return report;
}

}  // namespace l2s::detail
