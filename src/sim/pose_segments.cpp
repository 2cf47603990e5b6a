#include "sim/pose_segments.hpp"

#include <sstream>

namespace l2s::sim::detail {

BoardPose between(const BoardPose& a, const BoardPose& b, double f) {
  const auto mix = [f](double u, double v) { return u + (v - u) * f; };
  return {mix(a.x, b.x), mix(a.y, b.y), mix(a.z, b.z), mix(a.yaw, b.yaw), mix(a.pitch, b.pitch), mix(a.roll, b.roll)};
}

std::vector<PoseSegment> plan_segments(const std::vector<BoardPose>& poses, int frames_per_pose, int moving) {
  std::vector<PoseSegment> segments;
  int frames = 0;
  const auto add = [&](const BoardPose& pose, int count, int pose_index) {
    segments.push_back({pose, frames, count, pose_index});
    frames += count;
  };
  for (std::size_t p = 0; p < poses.size(); ++p) {
    if (p > 0)
      for (int m = 1; m <= moving; ++m) add(between(poses[p - 1], poses[p], m / (moving + 1.0)), 1, -1);
    add(poses[p], frames_per_pose, static_cast<int>(p));
  }
  return segments;
}

std::vector<int> moving_frames(const std::vector<PoseSegment>& segments) {
  std::vector<int> out;
  for (const PoseSegment& s : segments)
    if (s.pose_index < 0)
      for (int i = 0; i < s.frames; ++i) out.push_back(s.first_frame + i);
  return out;
}

std::vector<BoardPose> static_poses(const std::vector<PoseSegment>& segments) {
  std::vector<BoardPose> out;
  for (const PoseSegment& s : segments)
    if (s.pose_index >= 0) out.push_back(s.pose);
  return out;
}

std::string poses_yaml(const std::vector<PoseSegment>& segments) {
  std::ostringstream out;
  out.precision(9);
  out << "# Board poses of this recording, camera body frame (scene.yaml's board_pose convention).\n"
         "# pose: -1 marks a frame taken while the board was carried between two poses.\n"
         "segments:\n";
  for (const PoseSegment& s : segments)
    out << "  - {pose: " << s.pose_index << ", first_frame: " << s.first_frame << ", frames: " << s.frames
        << ", x: " << s.pose.x << ", y: " << s.pose.y << ", z: " << s.pose.z << ", yaw: " << s.pose.yaw
        << ", pitch: " << s.pose.pitch << ", roll: " << s.pose.roll << "}\n";
  return out.str();
}

}  // namespace l2s::sim::detail
