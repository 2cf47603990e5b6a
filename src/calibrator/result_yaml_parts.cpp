// Parts of the calibration result files shared by the lidar-camera and the
// lidar-lidar results (result_yaml.cpp, lidar_pair_result_yaml.cpp).

#include "calibrator/result_yaml_parts.hpp"

#include "io/yaml_helpers.hpp"

#include <l2s/fit_uncertainty.hpp>
#include <l2s/pose.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace l2s::io::result_parts {

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

void emit_transforms(YAML::Emitter& out, const Eigen::Isometry3d& T_a_b, const std::string& a, const std::string& b,
                     const std::string& frame_a, const std::string& frame_b) {
  yaml::emit_transform(out, "T_" + a + "_" + b, T_a_b);
  yaml::emit_transform(out, "T_" + b + "_" + a, T_a_b.inverse());
  emit_pose_details(out, a + "_" + b, T_a_b);
  emit_pose_details(out, b + "_" + a, T_a_b.inverse());
  out << YAML::Key << "static_transform_publisher" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "parent_" + a + "_child_" + b << YAML::Value << static_transform_arguments(T_a_b, frame_a, frame_b);
  out << YAML::Key << "parent_" + b + "_child_" + a << YAML::Value
      << static_transform_arguments(T_a_b.inverse(), frame_b, frame_a);
  out << YAML::EndMap;
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

/// Per DoF, translations in metres and rotations in degrees: {tx_m: .., roll_deg: ..}.
void emit_dofs(YAML::Emitter& out, const std::string& key, const std::array<double, 6>& values) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (int k = 0; k < 6; ++k)
    out << YAML::Key << std::string(dof_names()[k]) + (k < 3 ? "_m" : "_deg") << YAML::Value
        << format_number(k < 3 ? values[k] : values[k] * 180.0 / M_PI);
  out << YAML::EndMap;
}

void emit_uncertainty(YAML::Emitter& out, const JointRegistrar::Result& joint, int poses_used) {
  const FitUncertainty& u = joint.uncertainty;
  if (!u.valid) return;
  out << YAML::Key << "uncertainty" << YAML::Value << YAML::BeginMap;
  emit_dofs(out, "sigma", u.sigma);
  emit_dofs(out, "bound_95", u.bound_95);
  // One number each, what the verdict's trusted bounds are compared with.
  out << YAML::Key << "bound_95_translation_m" << YAML::Value << format_number(translation_bound_95(u));
  out << YAML::Key << "bound_95_rotation_deg" << YAML::Value
      << format_number(rotation_bound_95(u, joint.T_target_source) * 180.0 / M_PI);
  if (poses_used >= 3) emit_dofs(out, "sigma_between_poses", u.sigma_between_poses);
  if (*std::max_element(u.sigma_shared.begin(), u.sigma_shared.end()) > 0.0)
    emit_dofs(out, "sigma_shared", u.sigma_shared);
  out << YAML::Key << "residual_sigma_m" << YAML::Value << format_number(u.sigma_residual);
  out << YAML::Key << "dof" << YAML::Value << u.dof;
  out << YAML::Key << "condition" << YAML::Value << format_number(u.condition);
  out << YAML::Key << "weakest" << YAML::Value << u.weakest_summary;
  if (!u.suggestion.empty()) out << YAML::Key << "suggestion" << YAML::Value << "add a pose " + u.suggestion;
  out << YAML::EndMap;
}

void emit_leave_one_out(YAML::Emitter& out, const JointRegistrar::Result& joint, const std::vector<bool>& used_poses) {
  if (joint.leave_one_out.empty()) return;
  out << YAML::Key << "leave_one_pose_out" << YAML::Value << YAML::BeginSeq;
  for (std::size_t k = 0, used = 0; k < used_poses.size(); ++k) {
    if (!used_poses[k] || used >= joint.leave_one_out.size()) continue;
    const JointRegistrar::LeaveOneOut& loo = joint.leave_one_out[used++];
    out << YAML::BeginMap << YAML::Key << "pose" << YAML::Value << k;
    out << YAML::Key << "translation_m" << YAML::Value << format_number(loo.translation);
    out << YAML::Key << "rotation_deg" << YAML::Value << format_number(loo.rotation * 180.0 / M_PI);
    emit_dofs(out, "shift", loo.shift);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

}  // namespace l2s::io::result_parts
