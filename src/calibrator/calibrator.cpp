#include <l2s/calibrator.hpp>

#include "calibrator/branches.hpp"
#include "calibrator/check_keeper.hpp"
#include "calibrator/lidar_detector.hpp"
#include "calibrator/marker_placements.hpp"
#include "calibrator/pose_registration.hpp"
#include "calibrator/result_check.hpp"
#include "detail/board_frame.hpp"
#include "detail/input_checks.hpp"
#include "plane/plane_fit.hpp"

#include <l2s/check_frames.hpp>
#include <l2s/error.hpp>

#include <chrono>
#include <functional>
#include <future>
#include <optional>
#include <sstream>

namespace l2s {
namespace {

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template <class Branch>
BranchReport timed(Branch&& branch) {
  const auto start = std::chrono::steady_clock::now();
  BranchReport report = branch();
  report.milliseconds = milliseconds_since(start);
  return report;
}

/// The camera's board pose from its four centres alone (the plane through
/// them), for frames whose camera branch ran without a trace.
CameraObservation observation_from_centers(const HoleCenters& centers) {
  CameraObservation out;
  const std::vector<Eigen::Vector3d> points(centers.begin(), centers.end());
  const Plane plane = detail::fit_plane(points, {0, 1, 2, 3});
  out.T_camera_board = detail::board_pose_from_centers(centers, plane);
  return out;
}

/// A frame without the board still tests a transform by its depth edges
/// against the image's and its returns against the stereo depth.
bool has_scene_evidence(const CheckFrame& frame) {
  const bool lidar = !frame.lidar.scene_edges.empty() || !frame.lidar.scene.empty();
  return lidar && (!frame.camera.edges.empty() || !frame.camera.depth.empty());
}

}  // namespace

struct Calibrator::Impl {
  StereoCamera cameras;  // mono: the left camera alone (right default-constructed)
  // The camera side: a stereo pair (rectified cameras, and the rectifier for
  // raw images) or one camera finding the board by its markers.
  std::optional<detail::CameraSetup> camera_setup;
  std::shared_ptr<const MonoBoardDetector> mono;
  Target target;
  Params params;
  bool check = false;  // the scene check runs (params.check_result)
  std::vector<FrameReport> frames;
  SceneObserver observer;
  detail::CheckFrameKeeper check_frames;
  detail::LidarDetector lidar{target, params};  // its ring-free window, when the lidar has no rings
  // Ring-free lidars: the camera's view of the board from a frame of the
  // window being accumulated. The window's detection comes with its last
  // sweep, whose images may not show the board; the board is static over the
  // window, so any of its frames with the board serves the check; one whose
  // rim refinement converged, when one did (SceneScorer measures the board
  // on refined poses).
  std::shared_ptr<const CameraObservation> window_camera;
  bool ring_free_lidar = false;  // a frame's sweep had no ring structure
  // The accumulated cloud of the frames being added (AccumulatedLidar), and
  // the check's observation of it, made once.
  std::shared_ptr<const AccumulatedLidar::State> accumulated;
  std::optional<LidarObservation> accumulated_observation;

  struct LidarSide;
  LidarSide sweep_side(const LidarCloud& sweep, LidarInspection& trace);
  LidarSide accumulated_side(const AccumulatedLidar& cloud);
  FrameReport add_stereo(const LidarSide& side, const Image& left, const Image& right, const std::string& id);
  FrameReport add_mono(const LidarSide& side, const Image& left, const std::string& id);
  FrameReport add_with_camera(const LidarSide& side, const BranchReport& camera, const std::string& id);

  // Whether at least half of the frames whose camera found the board (and
  // one at least) found it by its marker corners alone, the rims not refined.
  bool mostly_posed_by_marker_corners() const {
    int found = 0, by_corners = 0;
    for (const FrameReport& frame : frames) {
      found += frame.camera.found;
      by_corners += frame.camera.found && frame.camera.markers > 0 && frame.camera.rim_rms_px == 0.0;
    }
    return by_corners > 0 && 2 * by_corners >= found;
  }

  // Names the frame, accumulates what its branches found, keeps its report,
  // and (for the frames the check keeps) what the check needs of it:
  // `observe_lidar()` and `observe_camera()` make that of this frame.
  template <class ObserveLidar, class ObserveCamera>
  FrameReport record(FrameReport report, const std::string& id, bool ring_free, ObserveLidar&& observe_lidar,
                     ObserveCamera&& observe_camera) {
    report.id = id.empty() ? std::to_string(frames.size()) : id;
    ring_free_lidar = ring_free_lidar || ring_free;
    std::shared_ptr<const CameraObservation> camera;  // of another frame of a ring-free window
    if (ring_free) {
      // A window this sweep closed at a move of the scene belongs with the
      // frame before, the last of its pose: there its centres meet the
      // camera's of that pose. The new window starts with this frame.
      detail::LidarDetector::WindowClose close = lidar.take_window_close();
      if (close.restarted) window_camera.reset();
      if (close.closed && !frames.empty())
        detail::LidarDetector::place_window(std::move(*close.closed), "ring-free window closed at a move of the scene",
                                            frames.back().lidar);
    }
    if (check && ring_free) {
      const bool refined = report.camera.found && report.camera.rim_rms_px > 0.0;
      const bool better = !window_camera || (!window_camera->board_pose_refined && refined);
      if (report.camera.found && better) window_camera = observe_camera();
      if (report.lidar.found && !refined && window_camera) camera = window_camera;
      if (report.lidar.failed_stage != "accumulating") window_camera.reset();  // the window is closed
    }
    if (check) {
      using Kind = detail::CheckFrameKeeper::Kind;
      const Kind kind = report.lidar.found && (report.camera.found || camera) ? Kind::Board : Kind::Scene;
      if (!check_frames.wants_next(kind)) {
        check_frames.skip(kind);
      } else {
        CheckFrame frame{report.id, observe_lidar(), camera ? *camera : *observe_camera()};
        // A frame the check cannot use counts as seen (the stride stays even).
        if (kind == Kind::Board || has_scene_evidence(frame))
          check_frames.keep(kind, std::move(frame));
        else
          check_frames.skip(kind);
      }
    }
    report.camera.observation.reset();  // held by the kept CheckFrame, if at all
    report.camera.check_left.reset();
    frames.push_back(report);
    return report;
  }

  // How the camera's board poses err with range: stereo measures it by
  // disparity over fx B (the rectified pair's), a mono camera by the
  // apparent size of the board's markers, spread over about its width. A
  // ring-free lidar's poses err more than the ring lidar's that the joint
  // fit's pose bias stands for.
  detail::SourceRange camera_range() const {
    const double base = mono ? cameras.left.fx() * target.board_width
                             : -camera_setup->cameras.right.projection_matrix(0, 3);
    detail::SourceRange range{base, params.camera_range_bias_px};
    // A stereo board posed by its marker corners alone (its rims not
    // refined) has the corners' disparity, good to about a tenth of a pixel,
    // not that of a rim fit over hundreds of edge samples.
    constexpr double kMarkerCornerDisparityPx = 0.1;
    if (!mono && mostly_posed_by_marker_corners())
      range.bias_px = std::max(range.bias_px, kMarkerCornerDisparityPx);
    if (ring_free_lidar) {
      range.extra_translation = detail::kRingFreePoseShare * params.joint.pose_bias_translation;
      range.extra_rotation = detail::kRingFreePoseShare * params.joint.pose_bias_rotation;
    }
    return range;
  }

  // Clusters the centres and registers them: the result before its check.
  Result registered() const {
    Result result;
    result.frames = frames;
    result.frames_added = static_cast<int>(frames.size());
    for (const auto& frame : frames) {
      result.lidar_frames += frame.lidar.found ? 1 : 0;
      result.camera_frames += frame.camera.found ? 1 : 0;
      result.lidar_ms += frame.lidar.milliseconds;
      result.camera_ms += frame.camera.milliseconds;
    }
    if (result.frames_added == 0) {
      result.reason = "no frames added";
      return result;
    }
    std::optional<HoleCenters> late_lidar;
    const std::optional<BranchReport> partial = lidar.partial_window();
    if (partial && partial->found) {
      late_lidar = partial->centers;
      ++result.lidar_frames;
    }
    const int needed = params.accumulator.min_frames;
    if (result.lidar_frames < needed || result.camera_frames < needed) {
      std::ostringstream reason;
      if (result.lidar_frames == 0 && result.camera_frames == 0)
        reason << "the board was never found in " << result.frames_added << " frames";
      else
        reason << "too few frames gave four centres: lidar " << result.lidar_frames << ", camera "
               << result.camera_frames << " of " << result.frames_added << " (need " << needed << ")";
      // The ring-free window still open says why it has no centres (a board
      // scanned too briefly: how many sweeps it takes).
      if (partial && !partial->found)
        reason << "; the ring-free window of the last " << lidar.window_size() << " sweep(s): " << partial->reason;
      result.reason = reason.str();
      return result;
    }

    if (!detail::register_poses(frames, late_lidar, target, params, camera_range(), result)) return result;
    result.found = true;
    return result;
  }

  Impl(StereoCamera c, Target t, Params p)
      : cameras(std::move(c)),
        camera_setup(std::in_place, cameras),
        target(t),
        params(std::move(p)),
        check(params.check_result),
        observer(params.observer),
        check_frames(params.check_frames) {}

  Impl(CameraInfo camera, ImageKind images, Target t, Params p)
      : cameras{std::move(camera), CameraInfo{}, images},
        mono(std::make_shared<const MonoBoardDetector>(cameras.left, images, t, p.mono)),
        target(t),
        params(std::move(p)),
        check(params.check_result),
        observer(params.observer),
        check_frames(params.check_frames) {}
};

Calibrator::Calibrator(StereoCamera cameras, Target target, Params params) {
  params.validate();
  target.validate();
  detail::check_cameras(cameras);
  impl_ = std::make_unique<Impl>(std::move(cameras), target, std::move(params));
}

Calibrator::Calibrator(CameraInfo camera, ImageKind images, Target target, Params params) {
  params.validate();
  target.validate();
  detail::check_camera(camera, "cameras.left");
  impl_ = std::make_unique<Impl>(std::move(camera), images, target, std::move(params));
}

Calibrator::~Calibrator() = default;
Calibrator::Calibrator(Calibrator&&) noexcept = default;
Calibrator& Calibrator::operator=(Calibrator&&) noexcept = default;

struct AccumulatedLidar::State {
  LidarCloud cloud;       // as given: the check observes its discontinuities
  LidarInspection trace;  // its detection's stages
  BranchReport report;
  bool ring_free = false;
};

const BranchReport& AccumulatedLidar::report() const {
  static const BranchReport kNone{};
  return state_ ? state_->report : kNone;
}

bool AccumulatedLidar::ring_free() const { return state_ && state_->ring_free; }

// The lidar side of a frame: a sweep through the detector (its ring-free
// window, when it has no rings), or an accumulated cloud detected once.
struct Calibrator::Impl::LidarSide {
  bool ring_free = false;
  std::function<BranchReport()> detect;
  std::function<LidarObservation(bool found)> observe;
};

Calibrator::Impl::LidarSide Calibrator::Impl::sweep_side(const LidarCloud& sweep, LidarInspection& trace) {
  LidarSide side;
  side.ring_free = detail::is_ring_free(sweep, params);
  side.detect = [this, &sweep, &trace, ring_free = side.ring_free] { return lidar.detect(sweep, ring_free, &trace); };
  side.observe = [this, &sweep, &trace](bool found) { return observe_lidar(sweep, trace, found, observer); };
  return side;
}

Calibrator::Impl::LidarSide Calibrator::Impl::accumulated_side(const AccumulatedLidar& cloud) {
  if (!cloud.state_) throw InputError("lidar", "an empty AccumulatedLidar (make it with detect_accumulated())");
  const std::shared_ptr<const AccumulatedLidar::State> state = cloud.state_;
  const bool first_use = state != accumulated;
  if (first_use) {
    accumulated = state;
    accumulated_observation.reset();
  }
  LidarSide side;
  side.ring_free = state->ring_free;
  side.detect = [state, first_use] {
    BranchReport report = state->report;
    if (!first_use) report.milliseconds = 0.0;  // its time counts once, with its first frame
    return report;
  };
  side.observe = [this, state](bool) {
    if (!accumulated_observation)
      accumulated_observation = observe_lidar(state->cloud, state->trace, state->report.found, observer);
    return *accumulated_observation;
  };
  return side;
}

FrameReport Calibrator::Impl::add_stereo(const LidarSide& side, const Image& left, const Image& right,
                                         const std::string& id) {
  const auto start = std::chrono::steady_clock::now();
  if (mono) throw InputError("right image", "given to a lidar-mono calibrator (add(lidar, left) takes one image)");
  // Here, not in the camera branch: an exception must leave before the lidar
  // branch runs and from the caller's thread.
  detail::check_stereo_images(left, right, cameras);
  // The traces cost nothing extra (the branches keep their stages in them
  // either way); the check observes the frames it keeps from them.
  CameraInspection camera_trace;
  const auto camera_branch = [&] {
    return timed([&] { return detail::run_camera_branch(left, right, *camera_setup, target, params, &camera_trace); });
  };

  FrameReport report;
  if (params.parallel_branches) {
    // The branches share nothing but const inputs; the camera side is the slower one.
    auto camera = std::async(std::launch::async, camera_branch);
    report.lidar = side.detect();
    report.camera = camera.get();
  } else {
    report.lidar = side.detect();
    report.camera = camera_branch();
  }
  std::shared_ptr<const CameraObservation> camera_observation;  // made once, when asked for
  const bool lidar_found = report.lidar.found, camera_found = report.camera.found;
  FrameReport recorded = record(
      std::move(report), id, side.ring_free, [&] { return side.observe(lidar_found); },
      [&] {
        if (!camera_observation)
          camera_observation = std::make_shared<const CameraObservation>(
              observe_camera(left, camera_trace, camera_found, cameras, observer));
        return camera_observation;
      });
  recorded.milliseconds = frames.back().milliseconds = milliseconds_since(start);
  return recorded;
}

FrameReport Calibrator::Impl::add_mono(const LidarSide& side, const Image& left, const std::string& id) {
  const auto start = std::chrono::steady_clock::now();
  // Before any work, from the caller's thread (as the stereo add()).
  if (!mono) throw InputError("right image", "missing: a stereo calibrator takes add(lidar, left, right)");
  detail::check_image(left, cameras.left, "left");
  const auto camera_branch = [&] { return timed([&] { return detail::run_mono_branch(left, *mono); }); };
  std::future<BranchReport> camera;
  if (params.parallel_branches) camera = std::async(std::launch::async, camera_branch);
  FrameReport report;
  report.lidar = side.detect();
  report.camera = camera.valid() ? camera.get() : camera_branch();
  // The check sees the left image's edges and the markers' board pose (no
  // stereo depth): made only for the frames it keeps.
  const std::shared_ptr<const CameraObservation> pose =
      report.camera.found ? report.camera.observation : std::shared_ptr<const CameraObservation>();
  const auto observe_camera = [&] {
    auto observation = std::make_shared<CameraObservation>(pose ? *pose : CameraObservation{});
    observation->edges = observer.observe_edges(left, cameras);
    return std::shared_ptr<const CameraObservation>(std::move(observation));
  };
  const bool lidar_found = report.lidar.found;
  FrameReport recorded =
      record(std::move(report), id, side.ring_free, [&] { return side.observe(lidar_found); }, observe_camera);
  recorded.milliseconds = frames.back().milliseconds = milliseconds_since(start);
  return recorded;
}

FrameReport Calibrator::Impl::add_with_camera(const LidarSide& side, const BranchReport& camera, const std::string& id) {
  FrameReport report;
  report.lidar = side.detect();
  report.camera = camera;
  report.milliseconds = report.lidar.milliseconds + camera.milliseconds;
  const bool lidar_found = report.lidar.found;
  return record(
      std::move(report), id, side.ring_free, [&] { return side.observe(lidar_found); },
      [&, observation = std::shared_ptr<const CameraObservation>()]() mutable {
        if (observation) return observation;  // asked twice for a ring-free window's frame
        if (!camera.observation)
          observation = std::make_shared<const CameraObservation>(
              camera.found ? observation_from_centers(camera.centers) : CameraObservation{});
        else if (!camera.check_left || !camera.observation->edges.empty())
          observation = camera.observation;
        else {
          auto complete = std::make_shared<CameraObservation>(*camera.observation);
          complete->edges = observer.observe_edges(*camera.check_left, camera_setup->cameras);
          observation = std::move(complete);
        }
        return observation;
      });
}

FrameReport Calibrator::add(const LidarCloud& lidar, const Image& left, const Image& right,
                            const std::string& id) {
  LidarInspection trace;
  return impl_->add_stereo(impl_->sweep_side(lidar, trace), left, right, id);
}

FrameReport Calibrator::add(const LidarCloud& lidar, const Image& left, const std::string& id) {
  LidarInspection trace;
  return impl_->add_mono(impl_->sweep_side(lidar, trace), left, id);
}

FrameReport Calibrator::add(const LidarCloud& lidar, const BranchReport& camera, const std::string& id) {
  LidarInspection trace;
  return impl_->add_with_camera(impl_->sweep_side(lidar, trace), camera, id);
}

AccumulatedLidar Calibrator::detect_accumulated(const LidarCloud& cloud) const {
  const Impl& impl = *impl_;
  const auto start = std::chrono::steady_clock::now();
  auto state = std::make_shared<AccumulatedLidar::State>();
  state->cloud = cloud;
  state->ring_free = detail::is_ring_free(cloud, impl.params);
  // A whole window already: detected as it stands, never windowed again.
  state->report = state->ring_free ? detail::run_ring_free_branch(detail::accumulate_ring_free({&cloud}, impl.params),
                                                                  impl.target, impl.params, &state->trace)
                                   : detail::run_lidar_branch(cloud, impl.target, impl.params, &state->trace);
  state->report.milliseconds = milliseconds_since(start);
  AccumulatedLidar out;
  out.state_ = std::move(state);
  return out;
}

FrameReport Calibrator::add(const AccumulatedLidar& lidar, const Image& left, const Image& right,
                            const std::string& id) {
  return impl_->add_stereo(impl_->accumulated_side(lidar), left, right, id);
}

FrameReport Calibrator::add(const AccumulatedLidar& lidar, const Image& left, const std::string& id) {
  return impl_->add_mono(impl_->accumulated_side(lidar), left, id);
}

FrameReport Calibrator::add(const AccumulatedLidar& lidar, const BranchReport& camera, const std::string& id) {
  return impl_->add_with_camera(impl_->accumulated_side(lidar), camera, id);
}

BranchReport Calibrator::camera_branch(const Image& left, const Image& right) const {
  const Impl& impl = *impl_;
  if (impl.mono) throw InputError("right image", "given to a lidar-mono calibrator (camera_branch(left) takes one image)");
  detail::check_stereo_images(left, right, impl.cameras);
  CameraInspection trace;
  BranchReport report = timed([&] {
    return detail::run_camera_branch(left, right, *impl.camera_setup, impl.target, impl.params, &trace);
  });
  // A frame without the board still shows the scene: add() checks with such
  // frames too, and add(lidar, camera) must check as add() would. The edges
  // (about 30 ms of a 1280x960 frame) wait for add() to keep the frame.
  if (impl.params.check_result) {
    report.observation = std::make_shared<const CameraObservation>(
        observe_camera(left, trace, report.found, impl.cameras, impl.observer, false));
    report.check_left = trace.rectified ? std::make_shared<const Image>(std::move(trace.rectified->left))
                                        : std::make_shared<const Image>(left);
  }
  return report;
}

BranchReport Calibrator::camera_branch(const Image& left) const {
  const Impl& impl = *impl_;
  if (!impl.mono) throw InputError("right image", "missing: a stereo calibrator takes camera_branch(left, right)");
  detail::check_image(left, impl.cameras.left, "left");
  return timed([&] { return detail::run_mono_branch(left, *impl.mono); });
}

bool Calibrator::mono() const { return impl_->mono != nullptr; }

Calibrator::Result Calibrator::result() const {
  const Impl& impl = *impl_;
  Result result = impl.registered();
  if (impl.mono) {
    detail::MarkerPlacements markers = detail::summarise_marker_placements(result.frames);
    result.marker_placements = std::move(markers.markers);
    result.notes.insert(result.notes.end(), markers.notes.begin(), markers.notes.end());
  }
  if (!result.found)
    result.quality.reasons = {"no transform to check: " + result.reason};
  else if (impl.params.check_result)
    // A stereo pair's markers label the camera's holes, not the lidar's: a
    // lidar mounted upside down labels its own turned by 180 deg, so the
    // check still weighs turned labels there (with the markers' labels
    // fixed, a marked board seen by an upside-down lidar came out 893 mm /
    // 180 deg off and `ok`).
    detail::check_result(result, impl.check_frames.frames(), impl.cameras, impl.target, impl.params,
                         impl.camera_range(), impl.mono != nullptr);
  return result;
}

void Calibrator::reset() {
  impl_->frames.clear();
  impl_->check_frames.reset();
  impl_->lidar.reset();
  impl_->window_camera.reset();
  impl_->ring_free_lidar = false;
  impl_->accumulated.reset();
  impl_->accumulated_observation.reset();
}

const std::vector<CheckFrame>& Calibrator::check_frames() const { return impl_->check_frames.frames(); }

int Calibrator::Result::poses_used() const {
  int used = 0;
  for (const PoseReport& pose : poses) used += pose.used;
  return used;
}

const Calibrator::Params& Calibrator::params() const { return impl_->params; }
const StereoCamera& Calibrator::cameras() const { return impl_->cameras; }
const Target& Calibrator::target() const { return impl_->target; }

}  // namespace l2s
