#include "calibrator/branches.hpp"

#include <l2s/io/image_io.hpp>

#include "detail/board_frame.hpp"

namespace l2s::detail {
namespace {

BranchReport fail(BranchReport report, const char* stage, const std::string& reason) {
  report.found = false;
  report.failed_stage = stage;
  report.reason = reason;
  return report;
}

StereoCloud subset(const StereoCloud& cloud, const std::vector<std::size_t>& indices) {
  StereoCloud out;
  out.points.reserve(indices.size());
  out.pixels.reserve(indices.size());
  for (const std::size_t i : indices) {
    out.points.push_back(cloud.points[i]);
    out.pixels.push_back(cloud.pixels[i]);
  }
  return out;
}

}  // namespace

BranchReport run_camera_branch(const Image& left, const Image& right, const StereoCamera& cameras,
                               const Target& target, const Calibrator::Params& params,
                               CameraInspection* trace) {
  CameraInspection local;
  CameraInspection& t = trace ? *trace : local;
  BranchReport report;
  const auto& stereo = t.stereo.emplace(StereoMatcher(params.stereo).match(left, right, cameras));
  if (!stereo.found) return fail(report, "stereo", stereo.reason);

  const auto& kept = t.pass_through.emplace(
      PassThroughFilter(params.camera_pass_through).filter(stereo.cloud.points));
  const StereoCloud& cloud = t.cloud = subset(stereo.cloud, kept.kept);
  report.input_points = cloud.size();
  if (cloud.size() < 3)
    return fail(report, "pass_through", "no stereo points inside the pass-through limits");

  const auto& plane =
      t.plane.emplace(PlaneSegmenter(params.camera_plane).segment(cloud.points, target));
  report.plane_inliers = plane.inliers.size();
  if (!plane.found) return fail(report, "plane", plane.reason);

  const auto& edges = t.edges.emplace(
      EdgeFilter(params.edges).filter(left, subset(cloud, plane.inliers), plane.plane, target));
  report.edge_points = edges.edges.size();
  if (!edges.found) return fail(report, "edges", edges.reason);

  const Eigen::Vector3d up_optical(0.0, -1.0, 0.0);
  const auto& circles =
      t.circles.emplace(CircleFinder(params.camera_circles)
                            .find(edges.edges.points, plane.plane, up_optical, target));
  report.fit_rms = circles.rms;
  if (!circles.found) return fail(report, "circles", circles.reason);
  report.centers = circles.centers;
  report.found = true;

  if (params.refine_camera_pose) {
    const auto& T_camera_board =
        t.T_camera_board_initial.emplace(board_pose_from_centers(circles.centers, plane.plane));
    const auto& refined = t.refined.emplace(BoardPoseRefiner(params.board_refiner)
                                                .refine(left, right, cameras, target, T_camera_board));
    // A refinement that stops on its round limit is usually still close (rms
    // ~0.1 px); keeping the stereo circles for such frames measured better on
    // the simulated suite than dropping them, and the accumulator's median
    // keeps the refined majority in charge.
    if (refined.converged) {
      report.centers = refined.centers;
      report.fit_rms = refined.rms_px;
    } else {
      report.note = "rim refinement did not converge (" + refined.reason + "); stereo circles kept";
    }
  } else if (trace) {
    t.T_camera_board_initial = board_pose_from_centers(circles.centers, plane.plane);
  }
  return report;
}

}  // namespace l2s::detail
