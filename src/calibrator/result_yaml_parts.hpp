#pragma once
// Parts of the calibration result files (private): shared by the
// lidar-camera result (result_yaml.cpp) and the lidar-lidar one
// (lidar_pair_result_yaml.cpp), so both read alike.

#include <l2s/calibrator.hpp>
#include <l2s/joint_registrar.hpp>

#include <yaml-cpp/yaml.h>

#include <array>
#include <string>
#include <vector>

namespace l2s::io::result_parts {

/// `name`: {translation, quaternion, rpy} of T.
void emit_pose_details(YAML::Emitter& out, const std::string& name, const Eigen::Isometry3d& T);

/// ROS static_transform_publisher arguments 'x y z yaw pitch roll parent child'
/// publishing T_parent_child (p_parent = T * p_child).
std::string static_transform_arguments(const Eigen::Isometry3d& T_parent_child, const std::string& parent,
                                       const std::string& child);

/// The transform keys of a result: T_<a>_<b> and its inverse, each with its
/// pose details, and the static_transform_publisher arguments both ways.
/// `frame_a`, `frame_b`: the ROS frame names of the two sensors.
void emit_transforms(YAML::Emitter& out, const Eigen::Isometry3d& T_a_b, const std::string& a, const std::string& b,
                     const std::string& frame_a, const std::string& frame_b);
/// `key`: the four hole centres by hole name.
void emit_centers(YAML::Emitter& out, const std::string& key, const HoleCenters& centers);

/// `key`: one branch's report of a frame (found, stage, reason, counts, time).
void emit_branch(YAML::Emitter& out, const std::string& key, const BranchReport& branch);

/// Per DoF, translations in metres and rotations in degrees: {tx_m: .., roll_deg: ..}.
void emit_dofs(YAML::Emitter& out, const std::string& key, const std::array<double, 6>& values);

/// `uncertainty` of the joint fit (nothing when it is not valid).
void emit_uncertainty(YAML::Emitter& out, const JointRegistrar::Result& joint, int poses_used);

/// `leave_one_pose_out`, numbered by pose among all found (`used_poses`: which joined the fit).
void emit_leave_one_out(YAML::Emitter& out, const JointRegistrar::Result& joint, const std::vector<bool>& used_poses);

}  // namespace l2s::io::result_parts
