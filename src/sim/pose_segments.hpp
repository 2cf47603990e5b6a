#pragma once
// The stretches of a multi-pose recording (private to the simulator): static
// board poses with moving frames between them, shared by the lidar-camera
// (multi_pose.cpp) and the lidar-lidar (lidar_pair.cpp) simulators.

#include <l2s/sim/multi_pose.hpp>

#include <string>
#include <vector>

namespace l2s::sim::detail {

/// The board a fraction `f` (0..1) of the way from `a` to `b`.
BoardPose between(const BoardPose& a, const BoardPose& b, double f);

/// `frames_per_pose` frames at each pose, and `moving` single frames with the
/// board on its way between consecutive poses, in time order.
std::vector<PoseSegment> plan_segments(const std::vector<BoardPose>& poses, int frames_per_pose, int moving);

/// The frames of the moving segments.
std::vector<int> moving_frames(const std::vector<PoseSegment>& segments);

/// The static poses, in order.
std::vector<BoardPose> static_poses(const std::vector<PoseSegment>& segments);

/// poses.yaml: one line per segment.
std::string poses_yaml(const std::vector<PoseSegment>& segments);

}  // namespace l2s::sim::detail
