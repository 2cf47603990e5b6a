// The two presets of the Calibrator: "paper" reproduces the 2017 method's
// parameters (paper Sec. IV-B); "default" is what measures best on the
// simulated suite (docs/simulator_and_suite.md, "Accuracy").

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>

#include <functional>

namespace l2s {
namespace {

// Prefixes a stage's ParamError with the Calibrator::Params field holding it.
void validate_field(const std::string& prefix, const std::function<void()>& validate) {
  try {
    validate();
  } catch (const ParamError& error) {
    throw ParamError(prefix + "." + error.field(), error.problem());
  }
}

}  // namespace

// The "default" preset: the stages' own defaults, and these.
Calibrator::Params::Params() {
  // The board is within a few metres of both sensors; far returns only slow the search.
  lidar_pass_through.max_range = 10.0;
  camera_pass_through.max_range = 10.0;
  // SGM on every other row: half the cost of the matching and of every later
  // stage, for a 10 Hz sensor. Rows only: at half resolution in both axes
  // SGBM's sub-pixel disparity locks to whole half-resolution pixels, so a
  // board at 3.5 m becomes terraces ~13 cm deep with a +-2 cm sawtooth, and
  // the 1 cm RANSAC consensus cuts it into board-sized strips (settings 3 and
  // 5 lost half their frames). Averaging rows keeps the disparity resolution
  // and lowers the noise of the board plane (rms 6 vs 10 mm at 3.6 m).
  stereo.row_downscale = 0.5;
  // A 64-beam sweep gives dozens of edge points per hole, hence many circle
  // candidates; 16 lost the true ones when a hole is cut by the top beam.
  lidar_circles.max_candidates = 32;
}

Calibrator::Params Calibrator::Params::preset(const std::string& name) {
  if (name == "default") return Params();
  if (name != "paper") throw ParamError("preset", "unknown preset '" + name + "' (expected default or paper)");

  // Sec. IV-B: delta_plane 1 cm, delta_inliers 5 cm (lidar) / 10 cm (camera),
  // delta_discont 50 cm, delta_cluster 2 cm, tau_sobel 128, alpha_plane 0.55 rad.
  // The pass-through range of the default preset stays (the paper's boxes are per setting).
  Params params;
  params.stereo.row_downscale = 1.0;  // SGM on every row
  params.lidar_plane = PlaneSegmenter::Params::lidar();
  params.lidar_plane.distance_threshold = 0.01;
  params.lidar_plane.inlier_threshold = 0.05;
  params.lidar_plane.max_angle = 0.55;
  params.camera_plane = PlaneSegmenter::Params::stereo();
  params.camera_plane.distance_threshold = 0.01;
  params.camera_plane.inlier_threshold = 0.10;
  params.camera_plane.max_angle = 0.55;
  params.camera_plane.remove_level_planes = 0;  // the paper segments the whole cloud
  params.discontinuity = DiscontinuityFilter::Params::paper();
  params.lidar_circles = CircleFinder::Params::paper();
  params.camera_circles = CircleFinder::Params::paper();
  params.edges.sobel_threshold = 128.0;
  params.refine_camera_pose = false;
  params.board_from_markers = false;  // the paper's board has no markers
  params.locate_board = false;  // one full-frame SGM pass, as the paper
  params.accumulator.cluster_tolerance = 0.02;
  params.accumulator.estimator = CenterAccumulator::Estimator::Mean;
  params.refine_with_board_planes = false;  // the paper registers the centres alone
  params.fit_lidar_rim_crossings = false;   // and clusters the frames' centres
  return params;
}

void Calibrator::Params::validate() const {
  validate_field("lidar_pass_through", [&] { lidar_pass_through.validate(); });
  validate_field("lidar_plane", [&] { lidar_plane.validate(); });
  validate_field("discontinuity", [&] { discontinuity.validate(); });
  validate_field("occupancy", [&] { occupancy.validate(); });
  validate_field("lidar_circles", [&] { lidar_circles.validate(); });
  validate_field("lidar_verifier", [&] { lidar_verifier.validate(); });
  validate_field("stereo", [&] { stereo.validate(); });
  validate_field("camera_pass_through", [&] { camera_pass_through.validate(); });
  validate_field("camera_plane", [&] { camera_plane.validate(); });
  validate_field("edges", [&] { edges.validate(); });
  validate_field("camera_circles", [&] { camera_circles.validate(); });
  validate_field("camera_verifier", [&] { camera_verifier.validate(); });
  validate_field("board_refiner", [&] { board_refiner.validate(); });
  validate_field("mono", [&] { mono.validate(); });
  validate_field("accumulator", [&] { accumulator.validate(); });
  validate_field("registrar", [&] { registrar.validate(); });
  validate_field("poses", [&] { poses.validate(); });
  validate_field("joint", [&] { joint.validate(); });
  if (ring_free_frames < 1) throw ParamError("ring_free_frames", "must be >= 1");
  if (check_frames < 1) throw ParamError("check_frames", "must be >= 1");
  if (!(camera_range_bias_px >= 0.0)) throw ParamError("camera_range_bias_px", "must be >= 0 px");
  if (!(trusted_bound_translation > 0.0)) throw ParamError("trusted_bound_translation", "must be > 0 m");
  if (!(trusted_bound_rotation_deg > 0.0)) throw ParamError("trusted_bound_rotation_deg", "must be > 0 deg");
  validate_field("observer", [&] { observer.validate(); });
  validate_field("check", [&] { check.validate(); });
}

}  // namespace l2s
