// The lidar-lidar simulator: a mount for lidar2 drawn near the first lidar,
// the board poses of a multi-pose recording that both lidars see
// (find_pose_spread with lidar2 among the lidars to pass), then
// per segment one scene, one ray caster and a LidarSimulator per lidar. No
// images are rendered, so a recording costs only its sweeps.

#include <l2s/sim/lidar_pair.hpp>

#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/pose.hpp>
#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/ray_caster.hpp>

#include "detail/atomic_file.hpp"
#include "sim/frame_writer.hpp"
#include "sim/pose_segments.hpp"
#include "sim/random.hpp"
#include "sim/scene_record.hpp"

#include <sstream>

namespace l2s::sim {
namespace {

constexpr std::uint64_t kMountStream = 0x2B1DULL;  // lidar2's pose draws
constexpr std::uint64_t kSweepStream = 0x5EE9ULL;  // per segment and lidar
constexpr int kMountDraws = 8;
constexpr int kChecked = 960;  // best-rated board poses checked per slot and mount

/// A mount of lidar2 relative to the first as on a vehicle or a sensor
/// bar: 0.3..1 m away, mostly sideways or fore-aft, yaw up to 20 deg, pitch
/// and roll up to 5 deg. Draw `k` of `seed`.
Eigen::Isometry3d draw_mount(std::uint64_t seed, int k) {
  const auto u = [&](int i) { return detail::uniform01(detail::hash_counters(seed, kMountStream, k, i)); };
  const double distance = 0.3 + 0.7 * u(0);
  const double azimuth = 2.0 * M_PI * u(1);
  const double dz = (2.0 * u(2) - 1.0) * 0.3 * distance;
  const double horizontal = std::sqrt(distance * distance - dz * dz);
  const Eigen::Vector3d t(horizontal * std::cos(azimuth), horizontal * std::sin(azimuth), dz);
  const double deg = M_PI / 180.0;
  return pose_from_roll_pitch_yaw((2.0 * u(3) - 1.0) * 5.0 * deg, (2.0 * u(4) - 1.0) * 5.0 * deg,
                                  (2.0 * u(5) - 1.0) * 20.0 * deg, t);
}

SensorSetting setting_of(const Eigen::Isometry3d& T_cambody_lidar) {
  const Eigen::Vector3d rpy = roll_pitch_yaw(T_cambody_lidar.rotation());
  const Eigen::Vector3d t = T_cambody_lidar.translation();
  return {t.x(), t.y(), t.z(), rpy[2], rpy[1], rpy[0]};
}

/// `base` with lidar2 at `setting` among the lidars every board pose must pass.
SimulationConfig with_lidar2(SimulationConfig base, const LidarModel& model, const SensorSetting& setting) {
  PlacementSearch search = base.placement_search.value_or(PlacementSearch{});
  search.also = {MountedLidar{model, setting}};
  // A mount that cannot see a slot is redrawn rather than searched to the end.
  if (search.max_checked == 0) search.max_checked = kChecked;
  base.placement_search = search;
  return base;
}

std::string lidar2_yaml(const LidarPairConfig& c, const SensorSetting& s) {
  std::ostringstream out;
  out.precision(9);
  out << "# The second lidar of this lidar-lidar recording (the calibrator never reads this file).\n"
      << "model: " << c.lidar2 << "\n"
      << "# its pose in the camera body frame, as scene.yaml's setting of the first lidar\n"
      << "setting: {tx: " << s.tx << ", ty: " << s.ty << ", tz: " << s.tz << ", yaw: " << s.yaw
      << ", pitch: " << s.pitch << ", roll: " << s.roll << "}\n";
  return out.str();
}

}  // namespace

void LidarPairConfig::validate() const {
  base.validate();
  LidarModel::by_name(lidar2).validate();
  if (poses < 1 || poses > 5) throw ParamError("poses", "must be 1..5");
  if (moving_frames < 0 || moving_frames > 10) throw ParamError("moving_frames", "must be 0..10");
  if (lidar2_setting)
    for (double v : {lidar2_setting->tx, lidar2_setting->ty, lidar2_setting->tz, lidar2_setting->yaw,
                     lidar2_setting->pitch, lidar2_setting->roll})
      if (!std::isfinite(v)) throw ParamError("lidar2_setting", "must be finite");
}

struct LidarPairSimulator::Impl {
  LidarPairConfig config;
  LidarModel model, model2;
  SensorSetting setting2;
  std::vector<PoseSegment> segments;
  std::vector<std::unique_ptr<RayCaster>> casters;                  // one per segment
  std::vector<std::array<std::unique_ptr<LidarSimulator>, 2>> lidars;  // per segment: lidar, lidar2
  std::vector<std::string> warnings;
  int frames = 0;

  std::vector<BoardPose> place();
  void build_segment(std::size_t k);
};

// Board poses both lidars see. A drawn mount of lidar2 is redrawn until
// every pose asked for is found (else the draw with the most poses is kept).
std::vector<BoardPose> LidarPairSimulator::Impl::place() {
  const SimulationConfig& base = config.base;
  const Eigen::Isometry3d T_cambody_lidar = base.setting.T_cambody_lidar();
  const int draws = config.lidar2_setting ? 1 : kMountDraws;
  std::vector<BoardPose> best;
  for (int k = 0; k < draws && static_cast<int>(best.size()) < config.poses; ++k) {
    const SensorSetting mount =
        config.lidar2_setting ? *config.lidar2_setting : setting_of(T_cambody_lidar * draw_mount(base.seed, k));
    std::vector<BoardPose> poses = find_pose_spread(with_lidar2(base, model2, mount), config.poses);
    if (k == 0 || poses.size() > best.size()) best = std::move(poses), setting2 = mount;
  }
  if (best.empty() && config.lidar2_setting && !base.strict_placement) {
    warnings.push_back("lidar2 sees none of the board poses the first lidar sees (placement check)");
    best = find_pose_spread(base, config.poses);
  }
  if (best.empty())
    throw Error("simulator: no board pose passes the placement check for both lidars" +
                std::string(config.lidar2_setting ? " (lidar2 at the given pose)" : " (any of the mounts drawn)"));
  if (static_cast<int>(best.size()) < config.poses)
    warnings.push_back("only " + std::to_string(best.size()) + " of " + std::to_string(config.poses) +
                       " board poses pass the placement check for both lidars");
  return best;
}

void LidarPairSimulator::Impl::build_segment(std::size_t k) {
  const SimulationConfig& c = config.base;
  casters.push_back(std::make_unique<RayCaster>(make_scene(c.target, segments[k].pose, c.layout)));
  std::array<std::unique_ptr<LidarSimulator>, 2> pair;
  const LidarModel* models[2] = {&model, &model2};
  for (std::uint64_t s = 0; s < 2; ++s) {
    LidarSimulator::Params p;
    p.noise_factor = c.noise_factor;
    p.seed = detail::hash_counters(c.seed, kSweepStream, k, s);
    p.threads = c.threads;
    p.beam_footprint = c.lidar_quirks.beam_footprint;
    p.return_mode = c.lidar_quirks.return_mode;
    pair[s] = std::make_unique<LidarSimulator>(*models[s], p);
  }
  lidars.push_back(std::move(pair));
  frames += segments[k].frames;
}

LidarPairSimulator::LidarPairSimulator(LidarPairConfig config) : impl_(std::make_unique<Impl>()) {
  config.validate();
  Impl& s = *impl_;
  s.config = std::move(config);
  const SimulationConfig& c = s.config.base;
  s.model = with_quirks(LidarModel::by_name(c.lidar), c.lidar_quirks);
  s.model2 = with_quirks(LidarModel::by_name(s.config.lidar2), c.lidar_quirks);
  const std::vector<BoardPose> poses = s.place();
  s.segments = detail::plan_segments(poses, c.frames, s.config.moving_frames);
  for (std::size_t k = 0; k < s.segments.size(); ++k) s.build_segment(k);
}

LidarPairSimulator::~LidarPairSimulator() = default;
LidarPairSimulator::LidarPairSimulator(LidarPairSimulator&&) noexcept = default;
LidarPairSimulator& LidarPairSimulator::operator=(LidarPairSimulator&&) noexcept = default;

int LidarPairSimulator::frames() const { return impl_->frames; }

SimulatedFrame LidarPairSimulator::frame(int index) const {
  const Impl& s = *impl_;
  if (index < 0 || index >= s.frames) throw ParamError("frame", "index out of range");
  std::size_t k = 0;
  while (index >= s.segments[k].first_frame + s.segments[k].frames) ++k;
  const auto local = static_cast<std::uint64_t>(index - s.segments[k].first_frame);
  SimulatedFrame out;
  out.lidar = s.lidars[k][0]->sweep(*s.casters[k], s.config.base.setting.T_cambody_lidar(), local);
  out.lidar2 = s.lidars[k][1]->sweep(*s.casters[k], s.setting2.T_cambody_lidar(), local);
  return out;
}

const std::vector<PoseSegment>& LidarPairSimulator::segments() const { return impl_->segments; }
std::vector<int> LidarPairSimulator::moving_frames() const { return detail::moving_frames(impl_->segments); }
std::vector<BoardPose> LidarPairSimulator::poses() const { return detail::static_poses(impl_->segments); }
const SensorSetting& LidarPairSimulator::lidar2_setting() const { return impl_->setting2; }
const LidarPairConfig& LidarPairSimulator::config() const { return impl_->config; }
std::vector<std::string> LidarPairSimulator::warnings() const { return impl_->warnings; }

Eigen::Isometry3d LidarPairSimulator::T_lidar_lidar2() const {
  return impl_->config.base.setting.T_cambody_lidar().inverse() * impl_->setting2.T_cambody_lidar();
}

void LidarPairSimulator::write(const std::string& folder, const ProgressCallback& progress) const {
  const Impl& s = *impl_;
  const io::DatasetWriter writer = io::DatasetWriter::lidar_pair(folder, s.config.base.target);
  writer.write_ground_truth_lidar2(T_lidar_lidar2());
  const BoardPose& first = s.segments.front().pose;
  const Scene scene = make_scene(s.config.base.target, first, s.config.base.layout);
  detail::write_scene_record(folder + "/scene.yaml", s.config.base, first, scene, s.model,
                             check_placement(scene, s.model, s.config.base.setting, s.config.base.rig));
  l2s::detail::write_file_atomically(folder + "/poses.yaml", detail::poses_yaml(s.segments));
  l2s::detail::write_file_atomically(folder + "/lidar2.yaml", lidar2_yaml(s.config, s.setting2));
  detail::write_frames(writer, s.frames, s.config.base.threads, [this](int i) { return frame(i); }, progress);
}

}  // namespace l2s::sim
