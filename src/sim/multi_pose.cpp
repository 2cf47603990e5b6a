// The multi-pose simulator: one DatasetSimulator per static pose (its frames
// share one clean render, as a single-pose dataset does) and one per moving
// frame (the board part of the way between two poses). Each stretch draws
// its noise from its own seed, derived from the config's.

#include <l2s/sim/multi_pose.hpp>

#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>

#include "detail/atomic_file.hpp"
#include "sim/frame_writer.hpp"
#include "sim/pose_segments.hpp"
#include "sim/random.hpp"
#include "sim/scene_record.hpp"

#include <sstream>

namespace l2s::sim {
namespace {

constexpr std::uint64_t kSegmentStream = 0x905EULL;

}  // namespace

void MultiPoseConfig::validate() const {
  base.validate();
  if (poses < 1 || poses > 5) throw ParamError("poses", "must be 1..5");
  if (moving_frames < 0 || moving_frames > 10) throw ParamError("moving_frames", "must be 0..10");
}

struct MultiPoseSimulator::Impl {
  MultiPoseConfig config;
  std::vector<PoseSegment> segments;
  std::vector<std::unique_ptr<DatasetSimulator>> simulators;  // one per segment
  std::vector<std::string> warnings;
  int frames = 0;

  // The simulator of segment k.
  void add(const PoseSegment& segment, std::size_t k) {
    SimulationConfig c = config.base;
    c.board_pose = segment.pose;
    c.frames = segment.frames;
    // The first stretch keeps the config's seed; the others derive theirs.
    if (k > 0) c.seed = detail::hash_counters(config.base.seed, kSegmentStream, k);
    c.strict_placement = segment.pose_index >= 0;  // a board on its way may leave the view
    simulators.push_back(std::make_unique<DatasetSimulator>(c));
    frames += segment.frames;
  }
};

MultiPoseSimulator::MultiPoseSimulator(MultiPoseConfig config) : impl_(std::make_unique<Impl>()) {
  config.validate();
  Impl& s = *impl_;
  s.config = std::move(config);
  const std::vector<BoardPose> poses = find_pose_spread(s.config.base, s.config.poses);
  if (poses.empty()) throw Error("simulator: no board pose passes the placement check for any slot of the view");
  if (static_cast<int>(poses.size()) < s.config.poses)
    s.warnings.push_back("only " + std::to_string(poses.size()) + " of " + std::to_string(s.config.poses) +
                         " board poses pass the placement check");
  s.segments = detail::plan_segments(poses, s.config.base.frames, s.config.moving_frames);
  for (std::size_t k = 0; k < s.segments.size(); ++k) s.add(s.segments[k], k);
}

MultiPoseSimulator::~MultiPoseSimulator() = default;
MultiPoseSimulator::MultiPoseSimulator(MultiPoseSimulator&&) noexcept = default;
MultiPoseSimulator& MultiPoseSimulator::operator=(MultiPoseSimulator&&) noexcept = default;

int MultiPoseSimulator::frames() const { return impl_->frames; }

SimulatedFrame MultiPoseSimulator::frame(int index) const {
  if (index < 0 || index >= impl_->frames) throw ParamError("frame", "index out of range");
  for (std::size_t k = 0; k < impl_->segments.size(); ++k) {
    const PoseSegment& s = impl_->segments[k];
    if (index < s.first_frame + s.frames) return impl_->simulators[k]->frame(index - s.first_frame);
  }
  throw ParamError("frame", "index out of range");  // not reached
}

const std::vector<PoseSegment>& MultiPoseSimulator::segments() const { return impl_->segments; }

std::vector<int> MultiPoseSimulator::moving_frames() const { return detail::moving_frames(impl_->segments); }
std::vector<BoardPose> MultiPoseSimulator::poses() const { return detail::static_poses(impl_->segments); }

Eigen::Isometry3d MultiPoseSimulator::T_lidar_camera() const { return impl_->config.base.T_lidar_camera(); }
StereoCamera MultiPoseSimulator::cameras() const { return impl_->config.base.rig.cameras(); }
const MultiPoseConfig& MultiPoseSimulator::config() const { return impl_->config; }
std::vector<std::string> MultiPoseSimulator::warnings() const { return impl_->warnings; }

void MultiPoseSimulator::write(const std::string& folder, const ProgressCallback& progress) const {
  const Impl& s = *impl_;
  const io::DatasetWriter writer(folder, cameras(), s.config.base.target,
                                 s.config.base.mono ? io::CameraLayout::Mono : io::CameraLayout::Stereo);
  writer.write_ground_truth(T_lidar_camera());
  const DatasetSimulator& first = *s.simulators.front();
  detail::write_scene_record(folder + "/scene.yaml", first.config(), first.board_pose(), first.scene(),
                             first.lidar_model(), first.placement());
  l2s::detail::write_file_atomically(folder + "/poses.yaml", detail::poses_yaml(s.segments));
  detail::write_frames(writer, s.frames, s.config.base.threads, [this](int i) { return frame(i); }, progress);
}

}  // namespace l2s::sim
