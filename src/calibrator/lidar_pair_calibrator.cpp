// LidarPairCalibrator: two LidarDetectors (one per lidar, so each ring-free
// lidar keeps its own window) feed two centre streams into the stereo
// Calibrator's pose registration (pose_registration.cpp), with the reference
// lidar as the target of the fit and lidar2 as its source.

#include <l2s/lidar_pair_calibrator.hpp>

#include "calibrator/lidar_detector.hpp"
#include "calibrator/pose_registration.hpp"

#include <chrono>
#include <cmath>
#include <future>
#include <sstream>

namespace l2s {
namespace {

/// Residual rms of a pose above which its centres are suspect: several times
/// the centre noise of a sweep averaged over a pose (a few mm), well below a
/// wrong hole pairing (tens of cm).
constexpr double kSuspectPoseRms = 0.02;  // [m]

LidarPairPoseReport pair_pose(const PoseReport& pose) {
  LidarPairPoseReport out;
  out.first_frame = pose.first_frame;
  out.last_frame = pose.last_frame;
  out.frames = pose.frames;
  out.lidar_centroids = pose.lidar_centroids;
  out.lidar2_centroids = pose.camera_centroids;  // stream 1 of the registration
  out.used = pose.used;
  out.reason = pose.reason;
  out.rms = pose.rms;
  return out;
}

/// Ok when every pose found joins the fit and each agrees within
/// kSuspectPoseRms; suspect otherwise; failed without a transform.
LidarPairCalibrator::Check check_result(const LidarPairCalibrator::Result& result) {
  LidarPairCalibrator::Check check;
  if (!result.found) {
    check.reasons.push_back("no transform: " + result.reason);
    return check;
  }
  for (std::size_t p = 0; p < result.poses.size(); ++p) {
    const LidarPairPoseReport& pose = result.poses[p];
    if (!pose.used) {
      check.reasons.push_back("pose " + std::to_string(p) + " not used: " + pose.reason);
      continue;
    }
    check.max_pose_rms = std::max(check.max_pose_rms, pose.rms);
    if (pose.rms > kSuspectPoseRms) {
      std::ostringstream why;
      why.precision(3);
      why << "pose " << p << ": the two lidars' centres differ by " << pose.rms * 1e3 << " mm rms under the result";
      check.reasons.push_back(why.str());
    }
  }
  check.verdict = check.reasons.empty() ? CalibrationCheck::Verdict::Ok : CalibrationCheck::Verdict::Suspect;
  return check;
}

}  // namespace

struct LidarPairCalibrator::Impl {
  Target target;
  Params params;
  detail::LidarDetector lidar{target, params};
  detail::LidarDetector lidar2{target, params};
  std::vector<LidarPairFrameReport> frames;

  Impl(Target t, Params p) : target(t), params(std::move(p)) {}

  /// Frame f's centres per lidar; a ring-free window detected as it stands
  /// counts with the last frame.
  std::vector<FrameCenters> streams() const {
    std::vector<FrameCenters> out;
    for (const LidarPairFrameReport& f : frames) {
      FrameCenters centres(2);
      if (f.lidar.found) centres[0] = f.lidar.centers;
      if (f.lidar2.found) centres[1] = f.lidar2.centers;
      out.push_back(std::move(centres));
    }
    const detail::LidarDetector* detectors[2] = {&lidar, &lidar2};
    for (int s = 0; s < 2 && !out.empty(); ++s)
      if (const auto partial = detectors[s]->partial_window(); partial && partial->found && !out.back()[s])
        out.back()[s] = partial->centers;
    return out;
  }

  /// Copies the registration (stream 0: lidar, stream 1: lidar2) into `result`.
  void registered(const std::vector<FrameCenters>& centres, Result& result) const {
    Calibrator::Result fit;
    const bool found = detail::register_pose_streams(centres, {"lidar", "lidar2"}, params, fit);
    for (const PoseReport& pose : fit.poses) result.poses.push_back(pair_pose(pose));
    result.moving_frames = fit.moving_frames;
    result.notes = fit.notes;
    result.registration = fit.registration;
    result.joint = fit.joint;
    result.found = found;
    result.reason = fit.reason;
    if (found) result.T_lidar_lidar2 = fit.T_lidar_camera;
  }
};

LidarPairCalibrator::LidarPairCalibrator(Target target, Params params) {
  params.validate();
  target.validate();
  impl_ = std::make_unique<Impl>(target, std::move(params));
}

LidarPairCalibrator::~LidarPairCalibrator() = default;
LidarPairCalibrator::LidarPairCalibrator(LidarPairCalibrator&&) noexcept = default;
LidarPairCalibrator& LidarPairCalibrator::operator=(LidarPairCalibrator&&) noexcept = default;

LidarPairFrameReport LidarPairCalibrator::add(const LidarCloud& lidar, const LidarCloud& lidar2,
                                              const std::string& id) {
  const auto start = std::chrono::steady_clock::now();
  Impl& impl = *impl_;
  LidarPairFrameReport report;
  report.id = id.empty() ? std::to_string(impl.frames.size()) : id;
  const auto second = [&] { return impl.lidar2.detect(lidar2, detail::is_ring_free(lidar2)); };
  if (impl.params.parallel_branches) {
    // The detectors share only const inputs.
    auto other = std::async(std::launch::async, second);
    report.lidar = impl.lidar.detect(lidar, detail::is_ring_free(lidar));
    report.lidar2 = other.get();
  } else {
    report.lidar = impl.lidar.detect(lidar, detail::is_ring_free(lidar));
    report.lidar2 = second();
  }
  report.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  impl.frames.push_back(report);
  return report;
}

LidarPairCalibrator::Result LidarPairCalibrator::result() const {
  const Impl& impl = *impl_;
  Result result;
  result.frames = impl.frames;
  result.frames_added = static_cast<int>(impl.frames.size());
  for (const LidarPairFrameReport& f : impl.frames) {
    result.lidar_ms += f.lidar.milliseconds;
    result.lidar2_ms += f.lidar2.milliseconds;
  }
  const std::vector<FrameCenters> centres = impl.streams();
  for (const FrameCenters& f : centres) {
    result.lidar_frames += f[0] ? 1 : 0;
    result.lidar2_frames += f[1] ? 1 : 0;
  }
  const int needed = impl.params.accumulator.min_frames;
  if (result.frames_added == 0) {
    result.reason = "no frames added";
  } else if (result.lidar_frames < needed || result.lidar2_frames < needed) {
    std::ostringstream reason;
    reason << "too few detections of four centres: lidar " << result.lidar_frames << ", lidar2 "
           << result.lidar2_frames << " of " << result.frames_added << " frames (need " << needed << ")";
    result.reason = reason.str();
  } else {
    impl.registered(centres, result);
  }
  result.check = check_result(result);
  return result;
}

void LidarPairCalibrator::reset() {
  impl_->frames.clear();
  impl_->lidar.reset();
  impl_->lidar2.reset();
}

int LidarPairCalibrator::Result::poses_used() const {
  int used = 0;
  for (const LidarPairPoseReport& pose : poses) used += pose.used;
  return used;
}

const LidarPairCalibrator::Params& LidarPairCalibrator::params() const { return impl_->params; }
const Target& LidarPairCalibrator::target() const { return impl_->target; }

}  // namespace l2s
