// The result file of a calibration: DATASET.md's T_lidar_camera first (tools
// that compare read only that key), then everything a user needs to apply and
// judge it.

#include <l2s/io/calibrator_yaml.hpp>

#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"

#include <l2s/center_accumulator.hpp>
#include <l2s/error.hpp>
#include <l2s/pose.hpp>

#include <cmath>
#include <sstream>

namespace l2s::io {
namespace {

using yaml::format_number;

void emit_pose_details(YAML::Emitter& out, const std::string& name, const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.rotation());
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.rotation());
  out << YAML::Key << name << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "translation" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "x" << YAML::Value << format_number(T.translation().x());
  out << YAML::Key << "y" << YAML::Value << format_number(T.translation().y());
  out << YAML::Key << "z" << YAML::Value << format_number(T.translation().z()) << YAML::EndMap;
  out << YAML::Key << "quaternion" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "x" << YAML::Value << format_number(q.x());
  out << YAML::Key << "y" << YAML::Value << format_number(q.y());
  out << YAML::Key << "z" << YAML::Value << format_number(q.z());
  out << YAML::Key << "w" << YAML::Value << format_number(q.w()) << YAML::EndMap;
  out << YAML::Key << "rpy" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "roll" << YAML::Value << format_number(rpy[0]);
  out << YAML::Key << "pitch" << YAML::Value << format_number(rpy[1]);
  out << YAML::Key << "yaw" << YAML::Value << format_number(rpy[2]) << YAML::EndMap;
  out << YAML::EndMap;
}

// ROS: static_transform_publisher x y z yaw pitch roll frame_id child_frame_id
// publishes the pose of child in frame_id, i.e. p_frame = T * p_child.
std::string static_transform_arguments(const Eigen::Isometry3d& T_parent_child,
                                       const std::string& parent, const std::string& child) {
  const Eigen::Vector3d t = T_parent_child.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T_parent_child.rotation());
  std::ostringstream args;
  args.precision(9);
  args << t.x() << " " << t.y() << " " << t.z() << " " << rpy[2] << " " << rpy[1] << " " << rpy[0]
       << " " << parent << " " << child;
  return args.str();
}

void emit_centers(YAML::Emitter& out, const std::string& key, const HoleCenters& centers) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  for (int i = 0; i < 4; ++i) {
    out << YAML::Key << hole_name(static_cast<Hole>(i)) << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int k = 0; k < 3; ++k) out << format_number(centers[i][k]);
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
}

void emit_branch(YAML::Emitter& out, const std::string& key, const BranchReport& branch) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "found" << YAML::Value << branch.found;
  if (!branch.found) {
    out << YAML::Key << "stage" << YAML::Value << branch.failed_stage;
    out << YAML::Key << "reason" << YAML::Value << branch.reason;
  }
  if (!branch.note.empty()) out << YAML::Key << "note" << YAML::Value << branch.note;
  out << YAML::Key << "plane_inliers" << YAML::Value << branch.plane_inliers;
  out << YAML::Key << "edge_points" << YAML::Value << branch.edge_points;
  out << YAML::Key << "ms" << YAML::Value << format_number(std::round(branch.milliseconds * 10) / 10);
  out << YAML::EndMap;
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
  yaml::emit_transform(out, "T_lidar_camera", T);
  yaml::emit_transform(out, "T_camera_lidar", T.inverse());
  emit_pose_details(out, "lidar_camera", T);
  emit_pose_details(out, "camera_lidar", T.inverse());

  out << YAML::Key << "static_transform_publisher" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "parent_lidar_child_camera" << YAML::Value
      << static_transform_arguments(T, "lidar", "camera_left_optical");
  out << YAML::Key << "parent_camera_child_lidar" << YAML::Value
      << static_transform_arguments(T.inverse(), "camera_left_optical", "lidar");
  out << YAML::EndMap;

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
