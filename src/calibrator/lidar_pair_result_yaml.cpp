// The lidar-lidar result file (lidar_pair_yaml.hpp), in the layout of the
// lidar-camera one (result_yaml.cpp) with lidar2 in the camera's place.

#include <l2s/io/lidar_pair_yaml.hpp>

#include "calibrator/result_yaml_parts.hpp"
#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"

#include <l2s/error.hpp>

#include <cmath>

namespace l2s::io {
namespace {

using yaml::format_number;
using namespace result_parts;

void emit_summary(YAML::Emitter& out, const LidarPairCalibrator::Result& result, const std::string& dataset,
                  const std::string& preset) {
  out << YAML::Key << "calibration" << YAML::Value << YAML::BeginMap;
  if (!dataset.empty()) out << YAML::Key << "dataset" << YAML::Value << dataset;
  if (!preset.empty()) out << YAML::Key << "preset" << YAML::Value << preset;
  out << YAML::Key << "frames_added" << YAML::Value << result.frames_added;
  out << YAML::Key << "lidar_frames" << YAML::Value << result.lidar_frames;
  out << YAML::Key << "lidar2_frames" << YAML::Value << result.lidar2_frames;
  out << YAML::Key << "residual_rms_m" << YAML::Value << format_number(result.registration.rms);
  out << YAML::Key << "residuals_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const double r : result.registration.residuals) out << format_number(r);
  out << YAML::EndSeq;
  out << YAML::Key << "check" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "verdict" << YAML::Value << verdict_name(result.check.verdict);
  out << YAML::Key << "max_pose_rms_m" << YAML::Value << format_number(result.check.max_pose_rms);
  out << YAML::Key << "reasons" << YAML::Value << YAML::BeginSeq;
  for (const auto& reason : result.check.reasons) out << reason;
  out << YAML::EndSeq << YAML::EndMap;
  out << YAML::Key << "notes" << YAML::Value << YAML::BeginSeq;
  for (const auto& note : result.notes) out << note;
  out << YAML::EndSeq << YAML::EndMap;
}

void emit_poses(YAML::Emitter& out, const LidarPairCalibrator::Result& result) {
  out << YAML::Key << "poses" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "found" << YAML::Value << result.poses.size();
  out << YAML::Key << "used" << YAML::Value << result.poses_used();
  out << YAML::Key << "moving_frames" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const int f : result.moving_frames) out << f;
  out << YAML::EndSeq;
  out << YAML::Key << "list" << YAML::Value << YAML::BeginSeq;
  std::vector<bool> used;
  for (const LidarPairPoseReport& pose : result.poses) {
    used.push_back(pose.used);
    out << YAML::BeginMap;
    out << YAML::Key << "first_frame" << YAML::Value << pose.first_frame;
    out << YAML::Key << "last_frame" << YAML::Value << pose.last_frame;
    out << YAML::Key << "frames" << YAML::Value << pose.frames.size();
    out << YAML::Key << "used" << YAML::Value << pose.used;
    if (std::isfinite(pose.rms)) out << YAML::Key << "rms_m" << YAML::Value << format_number(pose.rms);
    if (!pose.reason.empty()) out << YAML::Key << "reason" << YAML::Value << pose.reason;
    if (pose.lidar_centroids.found) emit_centers(out, "lidar_centroids", pose.lidar_centroids.centers);
    if (pose.lidar2_centroids.found) emit_centers(out, "lidar2_centroids", pose.lidar2_centroids.centers);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  emit_uncertainty(out, result.joint, result.poses_used());
  emit_leave_one_out(out, result.joint, used);
}

}  // namespace

void write_lidar_pair_result(const std::string& path, const LidarPairCalibrator::Result& result,
                             const std::string& dataset, const std::string& preset) {
  // A failed result holds an identity transform; written, it would pass for a calibration.
  if (!result.found)
    throw InputError("result", "the calibration failed (" + result.reason + "); not written to " + path);
  const Eigen::Isometry3d& T = result.T_lidar_lidar2;
  YAML::Emitter out;
  out << YAML::BeginMap;
  emit_transforms(out, T, "lidar", "lidar2", "lidar", "lidar2");
  emit_summary(out, result, dataset, preset);
  emit_poses(out, result);
  out << YAML::Key << "frames" << YAML::Value << YAML::BeginSeq;
  for (const LidarPairFrameReport& frame : result.frames) {
    out << YAML::BeginMap << YAML::Key << "id" << YAML::Value << frame.id;
    emit_branch(out, "lidar", frame.lidar);
    emit_branch(out, "lidar2", frame.lidar2);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  const std::string header =
      "# p_lidar = T_lidar_lidar2 * p_lidar2; both lidar frames x forward, y left, z up.\n"
      "# T_lidar2_lidar is its inverse. static_transform_publisher: ROS arguments\n"
      "# 'x y z yaw pitch roll parent child', i.e. p_parent = T * p_child.\n";
  l2s::detail::write_file_atomically(path, header + yaml::document_text(out));
}

}  // namespace l2s::io
