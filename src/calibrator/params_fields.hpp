#pragma once
// One list of the YAML keys of every stage's Params, walked by both the reader
// and the writer of calibrator params files, so the two can never disagree.

#include <l2s/calibrator.hpp>

namespace l2s::detail {

// Visitor V provides: field(name, T&) for double, int, bool, std::size_t,
// std::uint64_t, Eigen::Vector3d; choice(name, Enum&, names) for enums; and
// section(name, callable) for a nested mapping.

template <class V>
void visit(V& v, PassThroughFilter::Params& p) {
  v.field("min_xyz", p.min_xyz);
  v.field("max_xyz", p.max_xyz);
  v.field("min_range", p.min_range);
  v.field("max_range", p.max_range);
}

template <class V>
void visit(V& v, PlaneSegmenter::Params& p) {
  v.field("distance_threshold", p.distance_threshold);
  v.field("inlier_threshold", p.inlier_threshold);
  v.field("max_angle", p.max_angle);
  v.field("axis", p.axis);
  v.field("max_iterations", p.max_iterations);
  v.field("max_candidates", p.max_candidates);
  v.field("min_support", p.min_support);
  v.field("max_samples", p.max_samples);
  v.field("sample_radius", p.sample_radius);
  v.field("patch_gap_horizontal", p.patch_gap_horizontal);
  v.field("patch_gap_vertical", p.patch_gap_vertical);
  v.field("size_tolerance", p.size_tolerance);
  v.field("remove_level_planes", p.remove_level_planes);
  v.field("min_height_fraction", p.min_height_fraction);
  v.field("min_length_fraction", p.min_length_fraction);
  v.field("isolation_band", p.isolation_band);  // depth_noise: set per frame by the camera branch
  v.field("seed", p.seed);
}

template <class V>
void visit(V& v, DiscontinuityFilter::Params& p) {
  using P = DiscontinuityFilter::EdgePlacement;
  v.field("min_discontinuity", p.min_discontinuity);
  v.field("azimuth_step", p.azimuth_step);
  v.field("gap_factor", p.gap_factor);
  v.field("max_stray_points", p.max_stray_points);
  v.field("hole_gap_tolerance", p.hole_gap_tolerance);
  v.field("max_ring_edges", p.max_ring_edges);
  v.choice("placement", p.placement, {{P::LastBoardPoint, "last_board_point"}, {P::Midpoint, "midpoint"}});
}

template <class V>
void visit(V& v, OccupancyEdgeFilter::Params& p) {
  v.field("cell_factor", p.cell_factor);
  v.field("min_cell", p.min_cell);
  v.field("max_cell", p.max_cell);
  v.field("min_hole_depth", p.min_hole_depth);
  v.field("rim_sectors", p.rim_sectors);
}

template <class V>
void visit(V& v, CircleFinder::Params& p) {
  v.field("inlier_threshold", p.inlier_threshold);
  v.field("min_circle_points", p.min_circle_points);
  v.field("max_iterations", p.max_iterations);
  v.field("max_candidates", p.max_candidates);
  v.field("spacing_tolerance", p.spacing_tolerance);
  v.field("project_along_rays", p.project_along_rays);
  v.field("joint_fit", p.joint_fit);
  v.field("model_thickness", p.model_thickness);
  v.field("fit_radius", p.fit_radius);
  v.field("max_refine_iterations", p.max_refine_iterations);
  v.field("pattern_votes", p.pattern_votes);
  v.field("seed", p.seed);
}

template <class V>
void visit(V& v, BoardVerifier::Params& p) {
  v.field("hole_margin", p.hole_margin);
  v.field("outline_gap", p.outline_gap);
  v.field("outline_width", p.outline_width);
  v.field("min_samples", p.min_samples);
  v.field("min_hole_open", p.min_hole_open);
  v.field("min_look_difference", p.min_look_difference);
  v.field("min_outline_open", p.min_outline_open);
  v.field("min_rim_support", p.min_rim_support);
  v.field("min_rim_excess", p.min_rim_excess);
  v.field("confident_score", p.confident_score);
  v.field("max_hypotheses", p.max_hypotheses);
  v.field("challenger_prior", p.challenger_prior);
}

template <class V>
void visit(V& v, StereoMatcher::Params& p) {
  using M = StereoMatcher::Mode;
  v.field("block_size", p.block_size);
  v.field("p1", p.p1);
  v.field("p2", p.p2);
  v.field("disp12_max_diff", p.disp12_max_diff);
  v.field("pre_filter_cap", p.pre_filter_cap);
  v.field("uniqueness_ratio", p.uniqueness_ratio);
  v.field("speckle_window_size", p.speckle_window_size);
  v.field("speckle_range", p.speckle_range);
  v.choice("mode", p.mode, {{M::Sgbm5, "sgbm5"}, {M::Hh8, "hh8"}, {M::Sgbm3Way, "sgbm3way"}, {M::Hh4, "hh4"}});
  v.field("downscale", p.downscale);
  v.field("row_downscale", p.row_downscale);
  v.section("roi", [&](V& roi) {
    roi.field("x", p.roi.x);
    roi.field("y", p.roi.y);
    roi.field("width", p.roi.width);
    roi.field("height", p.roi.height);
  });
  v.field("min_depth", p.min_depth);
  v.field("max_depth", p.max_depth);
  v.field("guard_px", p.guard_px);
  v.field("disparity_sigma", p.disparity_sigma);
  v.field("stride", p.stride);
}

template <class V>
void visit(V& v, EdgeFilter::Params& p) {
  using M = EdgeFilter::Magnitude;
  v.field("sobel_threshold", p.sobel_threshold);
  v.field("adaptive_quantile", p.adaptive_quantile);
  v.field("adaptive_fraction", p.adaptive_fraction);
  v.field("min_sobel_threshold", p.min_sobel_threshold);
  v.field("noise_factor", p.noise_factor);
  v.field("region_dilation_px", p.region_dilation_px);
  v.choice("magnitude", p.magnitude, {{M::Hypot, "hypot"}, {M::HalfL1, "half_l1"}});
  v.field("colour", p.colour);
  v.field("remove_border_lines", p.remove_border_lines);
  v.field("line_distance", p.line_distance);
  v.field("line_iterations", p.line_iterations);
  v.field("max_border_lines", p.max_border_lines);
  v.field("min_line_points", p.min_line_points);
  v.field("max_line_tilt_deg", p.max_line_tilt_deg);
  v.field("min_border_fraction", p.min_border_fraction);
  v.field("max_gap", p.max_gap);
  v.field("seed", p.seed);
}

template <class V>
void visit(V& v, BoardPoseRefiner::Params& p) {
  v.field("samples_per_rim", p.samples_per_rim);
  v.field("search_range_px", p.search_range_px);
  v.field("search_step_px", p.search_step_px);
  v.field("first_edge_from_board", p.first_edge_from_board);
  v.field("min_edge_strength", p.min_edge_strength);
  v.field("rim_contrast_fraction", p.rim_contrast_fraction);
  v.field("edge_noise_factor", p.edge_noise_factor);
  v.field("huber_px", p.huber_px);
  v.field("max_iterations", p.max_iterations);
  v.field("gauss_newton_steps", p.gauss_newton_steps);
  v.field("image_margin_px", p.image_margin_px);
  v.field("converged_rotation", p.converged_rotation);
  v.field("converged_translation", p.converged_translation);
  v.field("converged_step_rms_fraction", p.converged_step_rms_fraction);
  v.field("min_edge_fraction", p.min_edge_fraction);
  v.field("use_right_image", p.use_right_image);
  v.field("min_samples", p.min_samples);
  v.field("max_rms_px", p.max_rms_px);
  v.field("fit_board_outline", p.fit_board_outline);
  v.field("outline_samples", p.outline_samples);
  v.field("outline_corner_gap", p.outline_corner_gap);
  v.field("min_outline_share", p.min_outline_share);
  v.field("max_outline_rms_px", p.max_outline_rms_px);
  v.field("max_outline_rim_growth", p.max_outline_rim_growth);
}

template <class V>
void visit(V& v, CenterAccumulator::Params& p) {
  using E = CenterAccumulator::Estimator;
  v.field("cluster_tolerance", p.cluster_tolerance);
  v.field("min_cluster_fraction", p.min_cluster_fraction);
  v.field("max_cluster_fraction", p.max_cluster_fraction);
  v.field("min_frames", p.min_frames);
  v.choice("estimator", p.estimator, {{E::Mean, "mean"}, {E::GeometricMedian, "geometric_median"}});
  v.field("align_labels", p.align_labels);
}

template <class V>
void visit(V& v, Registrar::Params& p) {
  v.field("min_extent", p.min_extent);
  v.field("min_planarity", p.min_planarity);
}

template <class V>
void visit(V& v, PoseGrouper::Params& p) {
  v.field("tolerance", p.tolerance);
  v.field("min_frames", p.min_frames);
}

template <class V>
void visit(V& v, JointRegistrar::Params& p) {
  v.field("outlier_ratio", p.outlier_ratio);
  v.field("outlier_floor", p.outlier_floor);
  v.field("min_poses_to_reject", p.min_poses_to_reject);
  v.field("max_condition", p.max_condition);
  v.field("pose_bias_translation", p.pose_bias_translation);
  v.field("pose_bias_rotation", p.pose_bias_rotation);
}

template <class V>
void visit(V& v, SceneObserver::Params& p) {
  v.field("min_jump", p.min_jump);
  v.field("relative_jump", p.relative_jump);
  v.field("gap_factor", p.gap_factor);
  v.field("min_range", p.min_range);
  v.field("grid_step", p.grid_step);
  v.field("board_band", p.board_band);
  v.field("max_edges", p.max_edges);
  v.field("max_board_points", p.max_board_points);
  v.field("max_scene_points", p.max_scene_points);
  v.field("canny_low", p.canny_low);
  v.field("canny_high", p.canny_high);
  v.field("strong_edge", p.strong_edge);
  v.field("depth_cell", p.depth_cell);
  v.field("depth_jump_margin", p.depth_jump_margin);
}

template <class V>
void visit(V& v, CalibrationCheck::Params& p) {
  v.field("edge_sigma_px", p.edge_sigma_px);
  v.field("max_edge_frames", p.max_edge_frames);
  v.field("scan_range_deg", p.scan_range_deg);
  v.field("depth_tolerance", p.depth_tolerance);
  v.field("outline_band", p.outline_band);
  v.field("suspect_misalignment_deg", p.suspect_misalignment_deg);
  v.field("failed_misalignment_deg", p.failed_misalignment_deg);
  v.field("suspect_roll_deg", p.suspect_roll_deg);
  v.field("failed_roll_deg", p.failed_roll_deg);
  v.field("suspect_scene_misalignment_deg", p.suspect_scene_misalignment_deg);
  v.field("failed_scene_misalignment_deg", p.failed_scene_misalignment_deg);
  v.field("suspect_outline_deg", p.suspect_outline_deg);
  v.field("failed_outline_deg", p.failed_outline_deg);
  v.field("suspect_plane_offset", p.suspect_plane_offset);
  v.field("min_plane_offset_px", p.min_plane_offset_px);
  v.field("failed_plane_offset", p.failed_plane_offset);
  v.field("suspect_stereo_offset_px", p.suspect_stereo_offset_px);
  v.field("failed_stereo_offset_px", p.failed_stereo_offset_px);
  v.field("row_texture_stereo_offset_px", p.row_texture_stereo_offset_px);
  v.field("row_texture_share", p.row_texture_share);
  v.field("suspect_plane_tilt_deg", p.suspect_plane_tilt_deg);
  v.field("failed_plane_tilt_deg", p.failed_plane_tilt_deg);
  v.field("suspect_pose_scatter_deg", p.suspect_pose_scatter_deg);
  v.field("failed_pose_scatter_deg", p.failed_pose_scatter_deg);
  v.field("suspect_center_offset", p.suspect_center_offset);
  v.field("failed_center_offset", p.failed_center_offset);
  v.field("suspect_outside_fraction", p.suspect_outside_fraction);
  v.field("failed_outside_fraction", p.failed_outside_fraction);
  v.field("suspect_alignment_gain", p.suspect_alignment_gain);
  v.field("min_misalignment_gain", p.min_misalignment_gain);
  v.field("min_optimum_edge_score", p.min_optimum_edge_score);
  v.field("min_misalignment_widths", p.min_misalignment_widths);
  v.field("refuting_center_offset", p.refuting_center_offset);
  v.field("min_roll_prominence", p.min_roll_prominence);
  v.field("suspect_depth_agreement", p.suspect_depth_agreement);
  v.field("failed_depth_agreement", p.failed_depth_agreement);
  v.field("failed_alignment_gain", p.failed_alignment_gain);
  v.field("suspect_depth_tilt_deg", p.suspect_depth_tilt_deg);
  v.field("failed_depth_tilt_deg", p.failed_depth_tilt_deg);
  v.field("suspect_depth_bias", p.suspect_depth_bias);
  v.field("failed_depth_bias", p.failed_depth_bias);
  v.field("min_edge_points", p.min_edge_points);
  v.field("min_scene_edge_points", p.min_scene_edge_points);
  v.field("min_prominence", p.min_prominence);
  v.field("hypothesis_margin", p.hypothesis_margin);
  v.field("upright_deg", p.upright_deg);
}

template <class V>
void visit(V& v, StereoBoardLocator::Params& p) {
  v.field("coarse_width", p.coarse_width);
  v.field("min_board_px", p.min_board_px);
  v.field("coarse_stride", p.coarse_stride);
  v.section("plane", [&](V& s) { visit(s, p.plane); });
  v.field("region_margin", p.region_margin);
  v.field("depth_margin", p.depth_margin);
}

template <class V>
void visit(V& v, MonoBoardDetector::Params& p) {
  v.field("min_markers", p.min_markers);
  v.field("max_marker_rms_px", p.max_marker_rms_px);
  v.field("marker_placement_tolerance", p.marker_placement_tolerance);
  v.field("refine_with_rims", p.refine_with_rims);
  v.field("marker_weight", p.marker_weight);
  v.section("rims", [&](V& s) { visit(s, p.rims); });
  v.field("max_rim_shift", p.max_rim_shift);
}

template <class V>
void visit(V& v, Calibrator::Params& p) {
  v.section("lidar_pass_through", [&](V& s) { visit(s, p.lidar_pass_through); });
  v.section("lidar_plane", [&](V& s) { visit(s, p.lidar_plane); });
  v.section("discontinuity", [&](V& s) { visit(s, p.discontinuity); });
  v.section("occupancy", [&](V& s) { visit(s, p.occupancy); });
  using S = Calibrator::LidarScan;
  v.choice("lidar_scan", p.lidar_scan, {{S::Auto, "auto"}, {S::Rings, "rings"}, {S::RingFree, "ring_free"}});
  v.field("ring_free_frames", p.ring_free_frames);
  v.section("lidar_circles", [&](V& s) { visit(s, p.lidar_circles); });
  v.section("lidar_verifier", [&](V& s) { visit(s, p.lidar_verifier); });
  v.section("stereo", [&](V& s) { visit(s, p.stereo); });
  v.section("camera_pass_through", [&](V& s) { visit(s, p.camera_pass_through); });
  v.field("locate_board", p.locate_board);
  v.section("locator", [&](V& s) { visit(s, p.locator); });
  v.section("camera_plane", [&](V& s) { visit(s, p.camera_plane); });
  v.section("edges", [&](V& s) { visit(s, p.edges); });
  v.section("camera_circles", [&](V& s) { visit(s, p.camera_circles); });
  v.section("camera_verifier", [&](V& s) { visit(s, p.camera_verifier); });
  v.field("refine_camera_pose", p.refine_camera_pose);
  v.field("board_from_markers", p.board_from_markers);
  v.section("board_refiner", [&](V& s) { visit(s, p.board_refiner); });
  v.section("mono", [&](V& s) { visit(s, p.mono); });
  v.section("accumulator", [&](V& s) { visit(s, p.accumulator); });
  v.section("registrar", [&](V& s) { visit(s, p.registrar); });
  v.section("poses", [&](V& s) { visit(s, p.poses); });
  v.section("joint", [&](V& s) { visit(s, p.joint); });
  v.field("camera_range_bias_px", p.camera_range_bias_px);
  v.field("refine_with_board_planes", p.refine_with_board_planes);
  v.field("fit_lidar_rim_crossings", p.fit_lidar_rim_crossings);
  v.field("parallel_branches", p.parallel_branches);
  v.field("check_result", p.check_result);
  v.field("check_frames", p.check_frames);
  v.section("observer", [&](V& s) { visit(s, p.observer); });
  v.section("check", [&](V& s) { visit(s, p.check); });
  v.field("trusted_bound_translation", p.trusted_bound_translation);
  v.field("trusted_bound_rotation_deg", p.trusted_bound_rotation_deg);
}

}  // namespace l2s::detail
