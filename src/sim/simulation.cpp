// The simulator facade: config -> scene (auto-placed board, checked) -> clean
// stereo pair rendered once -> per frame: fresh image noise and a lidar sweep.

#include <l2s/sim/simulation.hpp>

#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/ray_caster.hpp>

#include "sim/frame_writer.hpp"
#include "sim/random.hpp"
#include "sim/scene_record.hpp"

#include <cmath>

namespace l2s::sim {
namespace {

// Salts that give images and lidar independent random streams from one seed.
constexpr std::uint64_t kImageStream = 0x1A6EULL;
constexpr std::uint64_t kLidarStream = 0x71DAULL;

/// The markers moved and turned where the config glues them: the scene
/// shows them there, while the config's target keeps their nominal places.
void apply_marker_gluing(const SimulationConfig& config, Scene& scene) {
  if (config.marker_gluing.empty() || !scene.target.markers) return;
  for (std::size_t i = 0; i < config.marker_gluing.size(); ++i) {
    scene.target.markers->centres[i] += config.marker_gluing[i].head<2>();
    scene.marker_turns.push_back(config.marker_gluing[i].z());
  }
}

}  // namespace

SimulationConfig SimulationConfig::paper(int index, const std::string& lidar) {
  SimulationConfig config;
  config.setting_index = index;
  config.setting = paper_setting(index);
  config.lidar = lidar;
  LidarModel::by_name(lidar);  // reject unknown names here, not later
  return config;
}

void SimulationConfig::validate() const {
  if (setting_index < 0 || setting_index > 9)
    throw ParamError("setting", "must be 1..9 (Table I) or 0 (custom pose)");
  for (double v : {setting.tx, setting.ty, setting.tz, setting.yaw, setting.pitch, setting.roll})
    if (!std::isfinite(v)) throw ParamError("sensor_pose", "must be finite");
  LidarModel::by_name(lidar).validate();
  if (frames < 1 || frames > 1000000) throw ParamError("frames", "must be 1..1000000");
  if (!(noise_factor >= 0.0 && noise_factor <= 100.0)) throw ParamError("noise_factor", "must be 0..100");
  if (threads < 0) throw ParamError("threads", "must be >= 0 (0 = all cores)");
  if (!(accumulated_seconds >= 0.0 && accumulated_seconds <= 60.0))
    throw ParamError("accumulated_seconds", "must be 0..60 s (0: one sweep per frame)");
  if (!(accumulated_crop >= 0.0 && std::isfinite(accumulated_crop)))
    throw ParamError("accumulated_crop", "must be >= 0 m (0: no crop)");
  target.validate();
  if (!marker_gluing.empty() && (!target.markers || marker_gluing.size() != target.markers->ids.size()))
    throw ParamError("marker_gluing", "one entry per marker of the target, or none");
  for (const Eigen::Vector3d& gluing : marker_gluing)
    if (!gluing.allFinite() || gluing.head<2>().norm() > 0.05 || std::abs(gluing.z()) > 0.2)
      throw ParamError("marker_gluing", "a marker glued more than 5 cm or 0.2 rad off its place is another layout");
  if (mono && !target.markers)
    throw ParamError("mono", "a mono camera finds the board by its markers: the target has none (target.markers)");
  rig.validate();
  appearance.validate();
}

Eigen::Isometry3d SimulationConfig::T_lidar_camera() const {
  // The setting places the lidar relative to the camera body, the level
  // rig's left camera; the rig's roll turns the physical left camera in it,
  // and rectified images of a non-ideal rig live in another (rotated) frame.
  const Eigen::Isometry3d T_lidar_optical =
      rig.roll == 0.0 ? setting.T_lidar_camera() : setting.T_cambody_lidar().inverse() * rig.T_cambody_optical(0);
  if (rig.ideal() || rig.images() == ImageKind::Raw) return T_lidar_optical;
  return T_lidar_optical * rig.T_optical_camera();
}

struct DatasetSimulator::Impl {
  SimulationConfig config;
  LidarModel model;
  BoardPose pose;
  Scene scene;
  std::unique_ptr<RayCaster> caster;
  PlacementReport placement;
  std::vector<std::string> warnings;
  std::unique_ptr<StereoRenderer> renderer;
  std::unique_ptr<LidarSimulator> lidar;
  CleanStereo clean;
};

DatasetSimulator::DatasetSimulator(SimulationConfig config) : impl_(std::make_unique<Impl>()) {
  config.validate();
  Impl& s = *impl_;
  s.config = std::move(config);
  const SimulationConfig& c = s.config;
  s.model = with_quirks(LidarModel::by_name(c.lidar), c.lidar_quirks);

  if (c.board_pose) {
    s.pose = *c.board_pose;
  } else {
    // One pose for all three models, so a setting's scene does not depend on
    // the lidar; only if none exists, a pose for the configured model alone.
    // A ring-free lidar or one with its own laser table joins the three.
    PlacementSearch search = c.placement_search.value_or(PlacementSearch{});
    search.threads = c.threads;
    std::vector<LidarModel> joint{LidarModel::vlp16(), LidarModel::hdl32(), LidarModel::hdl64()};
    if (!s.model.has_rings() || !s.model.corrections.empty()) joint.push_back(s.model);
    PlacementResult found;
    if (!c.placement_search) found = find_placement(c.target, c.setting, joint, c.rig, c.layout, search);
    if (!found.found) found = find_placement(c.target, c.setting, {s.model}, c.rig, c.layout, search);
    s.pose = found.pose;
  }
  s.scene = make_scene(c.target, s.pose, c.layout);
  apply_marker_gluing(c, s.scene);
  s.caster = std::make_unique<RayCaster>(s.scene);
  s.placement = check_placement(s.scene, s.model, c.setting, c.rig);
  if (!s.placement.ok) {
    if (c.strict_placement)
      throw Error("simulator: the board placement does not satisfy the calibrator's needs (" +
                  std::string(c.board_pose ? "given" : "best found") + " pose)\n" +
                  s.placement.summary());
    s.warnings = s.placement.failures;
  }

  StereoRenderer::Params render_params;
  render_params.threads = c.threads;
  render_params.appearance = c.appearance;
  s.renderer = std::make_unique<StereoRenderer>(c.rig, render_params);
  LidarSimulator::Params lidar_params;
  lidar_params.noise_factor = c.noise_factor;
  lidar_params.seed = detail::hash_counters(c.seed, kLidarStream);
  lidar_params.threads = c.threads;
  lidar_params.beam_footprint = c.lidar_quirks.beam_footprint;
  lidar_params.return_mode = c.lidar_quirks.return_mode;
  s.lidar = std::make_unique<LidarSimulator>(s.model, lidar_params);
  if (c.mono)
    s.clean.left = s.renderer->render_camera(*s.caster, 0);
  else
    s.clean = s.renderer->render(*s.caster);
}

DatasetSimulator::~DatasetSimulator() = default;
DatasetSimulator::DatasetSimulator(DatasetSimulator&&) noexcept = default;
DatasetSimulator& DatasetSimulator::operator=(DatasetSimulator&&) noexcept = default;

SimulatedFrame DatasetSimulator::frame(int index) const {
  SimulatedFrame out = images(index);
  out.lidar = sweep(index);
  return out;
}

SimulatedFrame DatasetSimulator::images(int index) const {
  if (index < 0) throw ParamError("frame", "index must be >= 0");
  const Impl& s = *impl_;
  const auto frame = static_cast<std::uint64_t>(index);
  SimulatedFrame out;
  const std::uint64_t image_seed = detail::hash_counters(s.config.seed, kImageStream);
  if (s.config.mono) {
    // The left image's noise is the stereo dataset's, so both kinds of one config agree.
    out.left = s.renderer->add_noise(s.clean.left, s.config.noise_factor, image_seed, frame, 0);
    return out;
  }
  StereoImages images = s.renderer->add_noise(s.clean, s.config.noise_factor, image_seed, frame);
  out.left = std::move(images.left);
  out.right = std::move(images.right);
  return out;
}

LidarCloud DatasetSimulator::sweep(int index) const {
  if (index < 0) throw ParamError("frame", "index must be >= 0");
  const Impl& s = *impl_;
  return s.lidar->sweep(*s.caster, s.config.setting.T_cambody_lidar(), static_cast<std::uint64_t>(index));
}

LidarCloud DatasetSimulator::accumulated_cloud() const {
  const Impl& s = *impl_;
  const SimulationConfig& c = s.config;
  if (!(c.accumulated_seconds > 0.0)) throw ParamError("accumulated_seconds", "is 0: the dataset has one sweep per frame");
  constexpr double kSweepsPerSecond = 10.0;
  const int sweeps = std::max(1, static_cast<int>(std::lround(c.accumulated_seconds * kSweepsPerSecond)));
  const Eigen::Isometry3d T_board_lidar = (c.setting.T_cambody_lidar().inverse() * s.scene.T_cambody_board).inverse();
  const double half_width = 0.5 * c.target.board_width + c.accumulated_crop;
  const double half_height = 0.5 * c.target.board_height + c.accumulated_crop;
  const auto kept = [&](const Eigen::Vector3d& p) {
    if (c.accumulated_crop <= 0.0) return true;
    const Eigen::Vector3d b = T_board_lidar * p;
    return p.allFinite() && std::abs(b.x()) <= half_width && std::abs(b.y()) <= half_height &&
           std::abs(b.z()) <= c.accumulated_crop;
  };
  LidarCloud cloud;
  for (int i = 0; i < sweeps; ++i) {
    const LidarCloud one = sweep(i);
    for (std::size_t k = 0; k < one.size(); ++k) {
      if (!kept(one.points[k])) continue;
      cloud.points.push_back(one.points[k]);
      if (one.has_intensity()) cloud.intensity.push_back(one.intensity[k]);
      if (one.has_ring()) cloud.ring.push_back(one.ring[k]);
    }
  }
  if (cloud.intensity.size() != cloud.size()) cloud.intensity.clear();
  if (cloud.ring.size() != cloud.size()) cloud.ring.clear();
  return cloud;
}

void DatasetSimulator::write(const std::string& folder, const ProgressCallback& progress) const {
  const Impl& s = *impl_;
  const io::DatasetWriter writer(folder, cameras(), s.config.target,
                                 s.config.mono ? io::CameraLayout::Mono : io::CameraLayout::Stereo);
  writer.write_ground_truth(T_lidar_camera());
  detail::write_scene_record(folder + "/scene.yaml", s.config, s.pose, s.scene, s.model, s.placement);
  if (s.config.accumulated_seconds > 0.0) {
    // The images first, the cloud last: the dataset is whole once its lidar file exists.
    detail::write_frames(writer, s.config.frames, s.config.threads, [this](int i) { return images(i); }, progress,
                         detail::FrameFiles::Images);
    writer.write_accumulated_lidar(detail::stem_of(0), accumulated_cloud());
    return;
  }
  detail::write_frames(writer, s.config.frames, s.config.threads, [this](int i) { return frame(i); }, progress);
}

const SimulationConfig& DatasetSimulator::config() const { return impl_->config; }
const Scene& DatasetSimulator::scene() const { return impl_->scene; }
const BoardPose& DatasetSimulator::board_pose() const { return impl_->pose; }
const LidarModel& DatasetSimulator::lidar_model() const { return impl_->model; }
const PlacementReport& DatasetSimulator::placement() const { return impl_->placement; }
const CleanStereo& DatasetSimulator::clean_images() const { return impl_->clean; }
StereoCamera DatasetSimulator::cameras() const { return impl_->config.rig.cameras(); }
Eigen::Isometry3d DatasetSimulator::T_lidar_camera() const { return impl_->config.T_lidar_camera(); }
std::vector<std::string> DatasetSimulator::warnings() const { return impl_->warnings; }

DatasetSimulator::HoleTruth DatasetSimulator::true_hole_centers() const {
  const SimulationConfig& config = impl_->config;
  const Eigen::Isometry3d T_lidar_board = config.setting.T_cambody_lidar().inverse() * impl_->scene.T_cambody_board;
  const Eigen::Isometry3d T_camera_lidar = config.T_lidar_camera().inverse();
  const auto holes = config.target.hole_centers();
  HoleTruth truth;
  for (std::size_t h = 0; h < holes.size(); ++h) {
    truth.lidar[h] = T_lidar_board * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0);
    truth.camera[h] = T_camera_lidar * truth.lidar[h];
  }
  return truth;
}

std::vector<std::string> simulate_dataset(const SimulationConfig& config, const std::string& out_dir,
                                          const ProgressCallback& progress) {
  const DatasetSimulator simulator(config);
  simulator.write(out_dir, progress);
  return simulator.warnings();
}

}  // namespace l2s::sim
