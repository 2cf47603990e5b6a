// The result file of a calibration: DATASET.md's T_lidar_camera first (tools
// that compare read only that key), then everything a user needs to apply and
// judge it.

#include <l2s/io/calibrator_yaml.hpp>

#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"
#include "calibrator/result_yaml_parts.hpp"

#include <l2s/center_accumulator.hpp>
#include <l2s/fit_uncertainty.hpp>
#include <l2s/error.hpp>
#include <l2s/pose.hpp>

#include <cmath>
#include <sstream>

namespace l2s::io {
namespace {

using yaml::format_number;
using namespace result_parts;

void emit_scores(YAML::Emitter& out, const CalibrationCheck::Scores& s) {
  const auto number = [&](const char* key, double value) {
    if (std::isfinite(value)) out << YAML::Key << key << YAML::Value << format_number(value);
  };
  number("support", s.support);
  number("edge_score", s.edge_score);
  out << YAML::Key << "edge_points" << YAML::Value << s.edge_points;
  number("scene_edge_score", s.scene_edge_score);
  out << YAML::Key << "scene_edge_points" << YAML::Value << s.scene_edge_points;
  number("depth_agreement", s.depth_agreement);
  out << YAML::Key << "depth_points" << YAML::Value << s.depth_points;
  number("depth_bias", s.depth_bias);
  number("depth_tilt_deg", s.depth_tilt * 180.0 / M_PI);
  number("depth_tilt_sigma_deg", s.depth_tilt_sigma * 180.0 / M_PI);
  number("depth_tilt_texture", s.depth_tilt_texture);
  number("plane_offset_m", s.plane_offset);
  number("plane_offset_px", s.plane_offset_px);
  number("plane_spread_m", s.plane_spread);
  number("stereo_offset_m", s.stereo_offset);
  number("stereo_offset_px", s.stereo_offset_px);
  number("stereo_row_texture", s.stereo_row_texture);
  number("plane_tilt_deg", s.plane_tilt * 180.0 / M_PI);
  number("pose_scatter_deg", s.pose_scatter * 180.0 / M_PI);
  number("outline_px", s.outline_px);
  number("outside_fraction", s.outside_fraction);
  number("center_offset_m", s.center_offset);
}

// The calibration check (issue 11): verdict first, so a reader sees it at once.
void emit_quality(YAML::Emitter& out, const Calibrator::Result& result) {
  const CalibrationCheck::Report& q = result.quality;
  out << YAML::Key << "quality" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "verdict" << YAML::Value << verdict_name(q.verdict);
  out << YAML::Key << "reasons" << YAML::Value << YAML::BeginSeq;
  for (const auto& reason : q.reasons) out << reason;
  out << YAML::EndSeq;
  out << YAML::Key << "labels_turned_deg" << YAML::Value << result.labels_turned;
  out << YAML::Key << "notes" << YAML::Value << YAML::BeginSeq;
  for (const auto& note : result.notes) out << note;
  out << YAML::EndSeq;
  out << YAML::Key << "misalignment_px" << YAML::Value << format_number(q.misalignment_px);
  out << YAML::Key << "misalignment_deg" << YAML::Value << format_number(q.misalignment * 180.0 / M_PI);
  out << YAML::Key << "alignment_gain" << YAML::Value << format_number(q.alignment_gain);
  out << YAML::Key << "misalignment_gain" << YAML::Value << format_number(q.misalignment_gain);
  out << YAML::Key << "optimum_edge_score" << YAML::Value << format_number(q.optimum_edge_score);
  if (q.optimum_board) {
    // The board at the edges' best alignment: where it is far worse than in
    // `scores`, texture drew the edges there and the misalignment may not count.
    const CalibrationCheck::Scores& b = *q.optimum_board;
    out << YAML::Key << "optimum_board" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "center_offset_m" << YAML::Value << format_number(b.center_offset);
    out << YAML::Key << "outline_px" << YAML::Value << format_number(b.outline_px);
    out << YAML::Key << "outside_fraction" << YAML::Value << format_number(b.outside_fraction);
    out << YAML::Key << "plane_tilt_deg" << YAML::Value << format_number(b.plane_tilt * 180.0 / M_PI);
    out << YAML::EndMap;
  }
  out << YAML::Key << "edge_median_depth_m" << YAML::Value << format_number(q.median_depth);
  out << YAML::Key << "scores" << YAML::Value << YAML::BeginMap;
  emit_scores(out, q.scores);
  out << YAML::EndMap;
  // Per degree of freedom of the camera frame: where the edges align best
  // (offset) and how sharply (half width at half height).
  out << YAML::Key << "peaks" << YAML::Value << YAML::BeginMap;
  for (const auto& peak : q.peaks) {
    const double unit = peak.rotation ? 180.0 / M_PI : 1.0;
    out << YAML::Key << peak.name + (peak.rotation ? "_deg" : "_m") << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "offset" << YAML::Value << format_number(peak.offset * unit);
    out << YAML::Key << "width" << YAML::Value << format_number(peak.width * unit);
    out << YAML::Key << "prominence" << YAML::Value << format_number(peak.prominence);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::Key << "alternatives" << YAML::Value << YAML::BeginSeq;
  for (const auto& alternative : q.alternatives) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << alternative.name;
    emit_scores(out, alternative.scores);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "ambiguous" << YAML::Value << q.ambiguous;
  out << YAML::Key << "frames" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "board" << YAML::Value << q.board_frames;
  out << YAML::Key << "edges" << YAML::Value << q.edge_frames;
  out << YAML::Key << "depth" << YAML::Value << q.depth_frames << YAML::EndMap;
  out << YAML::Key << "ms" << YAML::Value << format_number(std::round(q.milliseconds * 10) / 10);
  out << YAML::EndMap;
}

// Several poses (issue 9): the poses found, the fit's uncertainty and how far
// leaving each pose out moves it.
void emit_poses(YAML::Emitter& out, const Calibrator::Result& result) {
  out << YAML::Key << "poses" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "found" << YAML::Value << result.poses.size();
  out << YAML::Key << "used" << YAML::Value << result.poses_used();
  out << YAML::Key << "moving_frames" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const int f : result.moving_frames) out << f;
  out << YAML::EndSeq;
  out << YAML::Key << "list" << YAML::Value << YAML::BeginSeq;
  for (const PoseReport& pose : result.poses) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "first_frame" << YAML::Value << pose.first_frame;
    out << YAML::Key << "last_frame" << YAML::Value << pose.last_frame;
    out << YAML::Key << "frames" << YAML::Value << pose.frames.size();
    out << YAML::Key << "used" << YAML::Value << pose.used;
    if (std::isfinite(pose.rms)) out << YAML::Key << "rms_m" << YAML::Value << format_number(pose.rms);
    out << YAML::Key << "lidar_centres" << YAML::Value << (pose.lidar_rims_fitted ? "rim_crossings" : "clustered");
    if (pose.lidar_rims_fitted)
      out << YAML::Key << "lidar_rim_radius_ratio" << YAML::Value << format_number(pose.lidar_rim_radius_ratio);
    for (const auto& [key, frames] : {std::pair{"lidar_outlier_frames", &pose.lidar_outlier_frames},
                                      std::pair{"camera_outlier_frames", &pose.camera_outlier_frames}}) {
      if (frames->empty()) continue;
      out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const int f : *frames) out << f;
      out << YAML::EndSeq;
    }
    if (!pose.reason.empty()) out << YAML::Key << "reason" << YAML::Value << pose.reason;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;

  emit_uncertainty(out, result.joint, result.poses_used());
  std::vector<bool> used;
  for (const PoseReport& pose : result.poses) used.push_back(pose.used);
  emit_leave_one_out(out, result.joint, used);
}

}  // namespace

void write_calibration_result(const std::string& path, const Calibrator::Result& result,
                              const std::string& dataset, const std::string& preset) {
  // A failed result holds an identity T_lidar_camera; written, it would pass
  // for a calibration with every tool that reads only that key.
  if (!result.found)
    throw InputError("result", "the calibration failed (" + result.reason + "); not written to " + path);
  const Eigen::Isometry3d& T = result.T_lidar_camera;
  YAML::Emitter out;
  out << YAML::BeginMap;
  emit_transforms(out, T, "lidar", "camera", "lidar", "camera_left_optical");

  out << YAML::Key << "calibration" << YAML::Value << YAML::BeginMap;
  if (!dataset.empty()) out << YAML::Key << "dataset" << YAML::Value << dataset;
  if (!preset.empty()) out << YAML::Key << "preset" << YAML::Value << preset;
  out << YAML::Key << "frames_added" << YAML::Value << result.frames_added;
  out << YAML::Key << "lidar_frames" << YAML::Value << result.lidar_frames;
  out << YAML::Key << "camera_frames" << YAML::Value << result.camera_frames;
  out << YAML::Key << "residual_rms_m" << YAML::Value << format_number(result.registration.rms);
  out << YAML::Key << "residuals_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const double r : result.registration.residuals) out << format_number(r);
  out << YAML::EndSeq;
  out << YAML::Key << "lidar_center_spread_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const double s : result.lidar_centroids.spread) out << format_number(s);
  out << YAML::EndSeq;
  out << YAML::Key << "camera_center_spread_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const double s : result.camera_centroids.spread) out << format_number(s);
  out << YAML::EndSeq;
  emit_centers(out, "lidar_centroids", result.lidar_centroids.centers);
  emit_centers(out, "camera_centroids", result.camera_centroids.centers);
  out << YAML::EndMap;
  emit_poses(out, result);
  if (result.checked) emit_quality(out, result);

  out << YAML::Key << "frames" << YAML::Value << YAML::BeginSeq;
  for (const auto& frame : result.frames) {
    out << YAML::BeginMap << YAML::Key << "id" << YAML::Value << frame.id;
    emit_branch(out, "lidar", frame.lidar);
    emit_branch(out, "camera", frame.camera);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;

  std::string text = yaml::transform_header_comment();
  text += "# T_camera_lidar is its inverse. static_transform_publisher: ROS arguments\n"
          "# 'x y z yaw pitch roll parent child', i.e. p_parent = T * p_child.\n";
  detail::write_file_atomically(path, text + yaml::document_text(out));
}

}  // namespace l2s::io
