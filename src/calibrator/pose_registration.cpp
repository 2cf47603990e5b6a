// Calibrator::result()'s registration over board poses (issue 9, "Several
// poses"): the frames' centres are grouped into poses (PoseGrouper on the
// lidar and camera streams), each pose's centres are clustered per sensor
// (CenterAccumulator, as the single-pose pipeline always did) and the poses
// whose centres cluster on both sides are fitted jointly (JointRegistrar).
// One static pose gives the old pipeline's result exactly.

#include "calibrator/pose_registration.hpp"

#include "calibrator/board_plane_refinement.hpp"
#include "circles/rim_crossing_fit.hpp"
#include "plane/plane_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace l2s::detail {
namespace {

std::vector<FrameCenters> observations(const std::vector<FrameReport>& frames,
                                       const std::optional<HoleCenters>& late_lidar) {
  std::vector<FrameCenters> out;
  for (const FrameReport& f : frames) {
    FrameCenters streams(2);
    if (f.lidar.found) streams[0] = f.lidar.centers;
    if (f.camera.found) streams[1] = f.camera.centers;
    out.push_back(std::move(streams));
  }
  if (late_lidar && !out.empty() && !out.back()[0]) out.back()[0] = *late_lidar;
  return out;
}

/// Frames of the stream `s` that hold centres.
int observed(const std::vector<FrameCenters>& streams, std::size_t s) {
  int count = 0;
  for (const FrameCenters& f : streams) count += f[s] ? 1 : 0;
  return count;
}

/// A stream with centres in far fewer frames than the other: a ring-free
/// lidar gives one set per window of sweeps (20 frames), at the window's last
/// frame. Its few sets cannot make or confirm a static stretch of their own,
/// so the poses are grouped on the other stream and each sparse set joins
/// the pose whose frames it lies among (or, past the last, the nearest one).
std::vector<bool> sparse_streams(const std::vector<FrameCenters>& streams) {
  std::vector<bool> sparse(2, false);
  const int lidar = observed(streams, 0), camera = observed(streams, 1);
  sparse[0] = lidar > 0 && 4 * lidar < camera;
  sparse[1] = camera > 0 && 4 * camera < lidar;
  return sparse;
}

/// The pose nearest in time to frame f (the one containing it, if any).
std::size_t pose_of_frame(const std::vector<PoseGrouper::Pose>& poses, int f) {
  std::size_t best = 0;
  int best_gap = std::numeric_limits<int>::max();
  for (std::size_t p = 0; p < poses.size(); ++p) {
    const int gap = f < poses[p].first ? poses[p].first - f : f > poses[p].last ? f - poses[p].last : 0;
    if (gap < best_gap) best_gap = gap, best = p;
  }
  return best;
}

/// Fewest frames of a pose with refined camera centres for its coarse ones
/// (the stereo circle fit of a frame whose rim refinement failed) to be left
/// out. The circle fit takes whatever edges lie near a rim: a textured
/// background seen through the holes (bricks, tiles) or a wood grain pulls
/// it by millimetres, and the same way in every frame of a static board, so
/// averaging does not remove it. Random scenes (30 frames) where it failed
/// in about half the frames: 1060328696 26.0 -> 5.2 mm and 0.60 -> 0.11 deg
/// with them left out, 1653306487 339 mm and 5.0 deg -> 5.3 mm, 0.09 deg.
constexpr int kMinRefinedFrames = 3;

/// Whether frame f's source centres are left out of the pose: coarse, in a
/// pose with at least kMinRefinedFrames frames of refined ones.
std::vector<bool> left_out_coarse(const PoseGrouper::Pose& pose, const std::vector<FrameCenters>& streams,
                                  const std::vector<bool>& coarse) {
  std::vector<bool> out(streams.size(), false);
  if (coarse.size() != streams.size()) return out;
  int refined = 0;
  for (int f : pose.frames) refined += streams[f][1] && !coarse[f] ? 1 : 0;
  if (refined < kMinRefinedFrames) return out;
  for (int f : pose.frames) out[f] = coarse[f];
  return out;
}

/// A pose's stream 0 centres as the target's pattern fitted to the rim
/// crossings of its `frames` (rim_crossing_fit.hpp); left as clustered, with
/// a note, when the crossings do not pin it.
void fit_rim_crossings(PoseReport& report, const std::vector<int>& frames, const TargetStreamEvidence& evidence,
                       const Calibrator::Params& params, const std::string& name, std::size_t index,
                       std::vector<std::string>& notes) {
  std::vector<RimCrossing> crossings;
  for (int f : frames)
    if (f < static_cast<int>(evidence.crossings.size()))
      crossings.insert(crossings.end(), evidence.crossings[f].begin(), evidence.crossings[f].end());
  if (crossings.empty()) return;  // a ring-free lidar: its occupancy edges have no azimuth steps
  RimCrossingFitParams fit_params;
  fit_params.model_thickness = params.lidar_circles.model_thickness;
  fit_params.fit_radius = params.lidar_circles.fit_radius;
  const RimCrossingFit fit = fit_pattern_to_rim_crossings(report.lidar_centroids.centers, *report.lidar_plane,
                                                          crossings, *evidence.target, fit_params);
  report.lidar_rims_fitted = fit.centers.has_value();
  if (fit.centers) {
    report.lidar_centroids.centers = *fit.centers;
    report.lidar_rim_radius_ratio = fit.radius / evidence.target->hole_radius;
  } else {
    notes.push_back("pose " + std::to_string(index) + ": the " + name + " centres are the clustered ones (" +
                    fit.reason + ")");
  }
}

/// The frames of stream `s` that `pose` left out: those the pose grouping
/// left out, and those of `added` whose centres the stream's clusters left
/// out, sorted.
std::vector<int> left_out_frames(const PoseGrouper::Pose& pose, std::size_t s, const std::vector<int>& added,
                                 const CenterAccumulator::Result& clusters) {
  std::vector<int> outliers = s < pose.stream_outliers.size() ? pose.stream_outliers[s] : std::vector<int>{};
  for (std::size_t k = 0; k < added.size() && k < clusters.clustered.size(); ++k)
    if (!clusters.clustered[k]) outliers.push_back(added[k]);
  std::sort(outliers.begin(), outliers.end());
  outliers.erase(std::unique(outliers.begin(), outliers.end()), outliers.end());
  return outliers;
}

PoseReport accumulate(const std::vector<PoseGrouper::Pose>& poses, std::size_t index,
                      const std::vector<FrameCenters>& streams, const std::vector<bool>& sparse,
                      const Calibrator::Params& params, const StreamNames& names,
                      const TargetStreamEvidence& evidence, const std::vector<bool>& coarse_source,
                      std::vector<std::string>& notes) {
  const PoseGrouper::Pose& pose = poses[index];
  PoseReport report;
  report.first_frame = pose.first;
  report.last_frame = pose.last;
  report.frames = pose.frames;
  report.rms = std::numeric_limits<double>::quiet_NaN();
  CenterAccumulator lidar(params.accumulator), camera(params.accumulator);
  CenterAccumulator* accumulators[2] = {&lidar, &camera};
  const auto wrong = [&](std::size_t s, int f) {
    if (s >= pose.stream_outliers.size()) return false;
    const std::vector<int>& bad = pose.stream_outliers[s];
    return std::find(bad.begin(), bad.end(), f) != bad.end();
  };
  const std::vector<bool> coarse = left_out_coarse(pose, streams, coarse_source);
  std::array<std::vector<int>, 2> added;  // the frame of each add() per stream
  int left_out = 0;
  for (int f : pose.frames)
    for (std::size_t s = 0; s < 2; ++s) {
      if (sparse[s] || !streams[f][s] || wrong(s, f)) continue;
      if (s == 1 && coarse[f]) {
        ++left_out;
        continue;
      }
      accumulators[s]->add(*streams[f][s]);
      added[s].push_back(f);
    }
  if (left_out > 0)
    notes.push_back("pose " + std::to_string(index) + ": the " + names[1] + " centres of " + std::to_string(left_out) +
                    " frame(s) whose rim refinement failed left out (the pose has enough refined ones)");
  for (std::size_t s = 0; s < 2; ++s)
    if (sparse[s])
      for (int f = 0; f < static_cast<int>(streams.size()); ++f)
        if (streams[f][s] && pose_of_frame(poses, f) == index) {
          accumulators[s]->add(*streams[f][s]);
          added[s].push_back(f);
        }
  const auto& planes = evidence.planes;
  std::vector<Plane> lidar_planes;
  std::vector<int> lidar_frames;
  for (int f : pose.frames) {
    if (wrong(0, f)) continue;
    lidar_frames.push_back(f);
    if (f < static_cast<int>(planes.size()) && planes[f]) lidar_planes.push_back(*planes[f]);
  }
  if (!lidar_planes.empty()) report.lidar_plane = mean_plane(lidar_planes);
  report.lidar_centroids = lidar.estimate();
  if (params.fit_lidar_rim_crossings && report.lidar_centroids.found && report.lidar_plane && evidence.target)
    fit_rim_crossings(report, lidar_frames, evidence, params, names[0], index, notes);
  report.camera_centroids = camera.estimate();
  report.lidar_outlier_frames = left_out_frames(pose, 0, added[0], report.lidar_centroids);
  report.camera_outlier_frames = left_out_frames(pose, 1, added[1], report.camera_centroids);
  if (!report.lidar_centroids.found)
    report.reason = names[0] + " centres do not cluster: " + report.lidar_centroids.reason;
  else if (!report.camera_centroids.found)
    report.reason = names[1] + " centres do not cluster: " + report.camera_centroids.reason;
  return report;
}

/// The joint fit as the single-pose Registrar::Result the result always had.
Registrar::Result as_registration(const JointRegistrar::Result& joint) {
  if (joint.used_count() == 1) return joint.single;
  Registrar::Result r;
  r.found = true;
  r.T_lidar_camera = joint.T_target_source;
  r.rms = joint.rms;
  for (int h = 0; h < 4; ++h) {
    double sum = 0.0;
    for (std::size_t k = 0; k < joint.used.size(); ++k)
      if (joint.used[k]) sum += joint.residuals[k][h] * joint.residuals[k][h];
    r.residuals[h] = std::sqrt(sum / joint.used_count());
  }
  return r;
}

/// The camera's board plane of a pose: through its four clustered centres
/// (which the rim fit puts on the board's front face), normal towards the camera.
Plane camera_plane(const HoleCenters& centers) {
  const std::vector<Eigen::Vector3d> points(centers.begin(), centers.end());
  return facing_origin(fit_plane(points, {0, 1, 2, 3}));
}

/// How far a lidar-camera pose's observations are trusted in the plane
/// refinement (1-sigma) when every pose's lidar centres were fitted to its
/// rim crossings. Those are off by 0.1-0.6 mm, the cameras' rim centres by
/// 0.05 mm across the line of sight but 0.3-0.9 mm along it, and the normal
/// through those four centres tilts by about 1 mrad with them (nine
/// settings, VLP-16, K = 1, 3 poses of 10 frames). Median e_t / e_r of
/// those runs: with the clustered centres' weights (the defaults),
/// 1.84 mm / 0.031 deg; with these, 0.69 mm / 0.017 deg; on recordings of
/// another seed, held out, 1.53 mm / 0.032 deg -> 0.86 mm / 0.018 deg.
/// Clustered lidar centres keep the defaults: with these weights they gave
/// 2.33 mm / 0.069 deg (defaults: 1.29 mm / 0.034 deg), their 1-1.5 mm
/// biases then outweigh the planes.
/// So do fitted ones whose holes look smaller than they are: a beam
/// footprint (the simulator's, 4.5 mm smaller radius at 3-4 m) biased them by
/// 1-1.7 mm, and these weights made the nine settings 3.55 mm / 0.069 deg
/// where the defaults give about 2 mm / 0.05 deg.
constexpr double kSharpRimRatio = 0.99;  ///< fitted radius over the target's: 0.997-1.003 without a footprint

BoardPlaneWeights camera_pose_weights(bool sharp_rims) {
  BoardPlaneWeights w;
  if (!sharp_rims) return w;
  w.centre_sigma = 0.0003;
  w.source_depth_sigma = 0.001;
  w.normal_sigma = 0.0012;
  return w;
}

/// The joint centre fit refined with the board planes of the used poses
/// (board_plane_refinement.hpp), when there are two or more. Residuals,
/// uncertainty and the leave-one-pose-out shifts stay those of the centre
/// fit. Measured on the nine settings (VLP-16, K = 1, 10 frames a pose):
/// 3 poses, median 2.1 -> 1.3 mm and 0.068 -> 0.034 deg; 1 pose,
/// 1.4 -> 1.9 mm and 0.065 -> 0.060 deg. One pose's camera plane offset is
/// then trusted beyond its accuracy, so a single pose keeps the centre fit.
void refine_with_planes(Calibrator::Result& result) {
  std::vector<BoardPoseObservation> poses;
  for (const PoseReport& pose : result.poses)
    if (pose.used && pose.lidar_plane)
      poses.push_back({pose.lidar_centroids.centers, pose.camera_centroids.centers, *pose.lidar_plane,
                       camera_plane(pose.camera_centroids.centers)});
  if (poses.size() < 2) return;
  const bool sharp_rims = lidar_centres_sharp(result.poses);
  const Eigen::Isometry3d refined =
      refine_with_board_planes(result.T_lidar_camera, poses, camera_pose_weights(sharp_rims));
  const Eigen::Isometry3d moved = result.T_lidar_camera.inverse() * refined;
  std::ostringstream note;
  note.precision(2);
  note << std::fixed << "refined with the board planes of " << poses.size() << " pose(s): moved "
       << moved.translation().norm() * 1e3 << " mm, " << Eigen::AngleAxisd(moved.linear()).angle() * 180.0 / M_PI
       << " deg" << (sharp_rims ? "; the lidar centres fitted to their rim crossings trusted to 0.3 mm" : "");
  result.notes.push_back(note.str());
  result.T_lidar_camera = refined;
}

/// The error a camera's board pose shares across its frames, camera frame:
/// its range errs by q bias_px along the line of sight (q = z^2 / base, the
/// range per pixel of disparity at the centres' range z), and the board
/// tilts across it by the depth error over the pattern's size. On 100
/// random scenes the rotation error grew with q alike: e_r / (q / 0.45 m)
/// had a median of 0.026 px and a 68th percentile of 0.046 px, i.e. about
/// 0.02-0.03 px per tilt axis (Calibrator::Params::camera_range_bias_px).
/// Since the rim refinement also fits the board's outline, the same 100
/// scenes give, where the term dominates (q >= 0.1 m/px, 32 results within
/// 2 deg), a median of 0.011 px and a 95th percentile of 0.041 px: a
/// maximum-likelihood 0.0145 px per tilt axis (0.021 before the outline),
/// but 0.017 by the 95th percentile. With 0.015 the 95 % bounds covered all
/// six DoFs in 75 % of the runs instead of 78 % (three results 9-26 mm off
/// lost a DoF), so 0.02 stays: the tail, not the median, sets a 95 % bound.
MotionCovariance camera_pose_bias(const HoleCenters& c, const SourceRange& range) {
  MotionCovariance bias = MotionCovariance::Zero();
  if (!(range.base > 0.0 && range.bias_px > 0.0)) return bias;
  const Eigen::Vector3d centroid = 0.25 * (c[0] + c[1] + c[2] + c[3]);
  const double z = centroid.norm();
  const double across = 0.5 * ((c[1] - c[0]).norm() + (c[3] - c[2]).norm());
  const double down = 0.5 * ((c[2] - c[0]).norm() + (c[3] - c[1]).norm());
  const double size = std::sqrt(across * down);
  if (!(z > 0.0 && size > 0.0)) return bias;
  const double depth_sigma = z * z / range.base * range.bias_px;
  const double tilt_sigma = depth_sigma / size;
  const Eigen::Vector3d u = centroid / z;
  const Eigen::Matrix3d along = u * u.transpose();
  bias.topLeftCorner<3, 3>() = depth_sigma * depth_sigma * along;
  bias.bottomRightCorner<3, 3>() = tilt_sigma * tilt_sigma * (Eigen::Matrix3d::Identity() - along);
  return bias;
}

/// All a pose's shares beyond the joint pose bias (SourceRange): the
/// camera's range and tilt, and the extra isotropic share.
MotionCovariance source_pose_bias(const HoleCenters& c, const SourceRange& range) {
  MotionCovariance bias = camera_pose_bias(c, range);
  bias.topLeftCorner<3, 3>().diagonal().array() += range.extra_translation * range.extra_translation;
  bias.bottomRightCorner<3, 3>().diagonal().array() += range.extra_rotation * range.extra_rotation;
  return bias;
}

/// Fits the poses whose centres cluster on both sides and records the fit.
bool fit_poses(Calibrator::Result& result, const Calibrator::Params& params, const SourceRange& source_range) {
  std::vector<PosePair> pairs;
  std::vector<int> fitted;  // index into result.poses of each pair
  std::ostringstream why;
  for (std::size_t p = 0; p < result.poses.size(); ++p) {
    PoseReport& pose = result.poses[p];
    if (!pose.lidar_centroids.found || !pose.camera_centroids.found) {
      why << (why.tellp() > 0 ? "; " : "") << "pose " << p << ": " << pose.reason;
      continue;
    }
    pairs.push_back({pose.lidar_centroids.centers, pose.camera_centroids.centers,
                     source_pose_bias(pose.camera_centroids.centers, source_range)});
    fitted.push_back(static_cast<int>(p));
  }
  if (pairs.empty()) {
    // One pose keeps the message of the single-pose pipeline.
    result.reason = result.poses.size() == 1 ? result.poses[0].reason : "no board pose is usable: " + why.str();
    if (result.poses.empty()) result.reason = "no board pose found";
    return false;
  }
  result.joint = JointRegistrar(params.joint, params.registrar).estimate(pairs);
  if (!result.joint.found) {
    result.reason = "registration failed: " + result.joint.reason;
    return false;
  }
  bool first = true;
  for (std::size_t k = 0; k < fitted.size(); ++k) {
    PoseReport& pose = result.poses[fitted[k]];
    pose.used = result.joint.used[k];
    pose.rms = result.joint.pose_rms[k];
    pose.reason = pose.used ? "" : "rejected: its centres disagree with the other poses";
    if (pose.used && first) {
      result.lidar_centroids = pose.lidar_centroids;
      result.camera_centroids = pose.camera_centroids;
      first = false;
    }
  }
  for (const std::string& note : result.joint.notes) {
    // JointRegistrar numbers the fitted poses; the result numbers all of them.
    std::string n = note;
    const std::size_t at = n.find("pose ");
    if (at == 0) {
      const int k = std::stoi(n.substr(5));
      n = "pose " + std::to_string(fitted[k]) + n.substr(5 + std::to_string(k).size());
    }
    result.notes.push_back(n);
  }
  result.registration = as_registration(result.joint);
  result.T_lidar_camera = result.joint.T_target_source;
  if (params.refine_with_board_planes) refine_with_planes(result);
  return true;
}

template <class T>
std::array<T, 4> permuted(const std::array<T, 4>& values, const HolePermutation& permutation) {
  std::array<T, 4> out;
  for (int h = 0; h < 4; ++h) out[h] = values[permutation[h]];
  return out;
}

}  // namespace

bool lidar_centres_sharp(const std::vector<PoseReport>& poses) {
  bool any = false;
  for (const PoseReport& pose : poses) {
    if (!(pose.used && pose.lidar_plane)) continue;
    if (!(pose.lidar_rims_fitted && pose.lidar_rim_radius_ratio > kSharpRimRatio)) return false;
    any = true;
  }
  return any;
}

bool register_poses(const std::vector<FrameReport>& frames, const std::optional<HoleCenters>& late_lidar,
                    const Target& target, const Calibrator::Params& params, const SourceRange& camera_range,
                    Calibrator::Result& result) {
  TargetStreamEvidence lidar;
  lidar.target = target;
  std::vector<bool> coarse_camera;
  for (const FrameReport& f : frames) {
    lidar.planes.push_back(f.lidar.found ? f.lidar.board_plane : std::nullopt);
    lidar.crossings.push_back(f.lidar.found ? f.lidar.rim_crossings : std::vector<RimCrossing>{});
    // rim_rms_px is 0 exactly when the centres are not the rim refinement's.
    coarse_camera.push_back(f.camera.found && params.refine_camera_pose && f.camera.rim_rms_px == 0.0);
  }
  return register_pose_streams(observations(frames, late_lidar), {"lidar", "camera"}, params, result, lidar,
                               coarse_camera, camera_range);
}

bool register_pose_streams(const std::vector<FrameCenters>& streams, const StreamNames& names,
                           const Calibrator::Params& params, Calibrator::Result& result,
                           const TargetStreamEvidence& lidar, const std::vector<bool>& coarse_source,
                           const SourceRange& source_range) {
  const std::vector<bool> sparse = sparse_streams(streams);
  std::vector<FrameCenters> dense = streams;
  for (FrameCenters& f : dense)
    for (std::size_t s = 0; s < 2; ++s)
      if (sparse[s]) f[s].reset();
  const PoseGrouper::Result grouping = PoseGrouper(params.poses).group(dense, {names[0], names[1]});
  result.moving_frames = grouping.moving;
  result.notes.insert(result.notes.end(), grouping.notes.begin(), grouping.notes.end());
  for (std::size_t p = 0; p < grouping.poses.size(); ++p)
    result.poses.push_back(
        accumulate(grouping.poses, p, streams, sparse, params, names, lidar, coarse_source, result.notes));
  return fit_poses(result, params, source_range);
}

bool refit_relabelled(Calibrator::Result& result, const HolePermutation& permutation,
                      const Calibrator::Params& params, const SourceRange& source_range) {
  Calibrator::Result turned = result;
  turned.notes.clear();
  for (PoseReport& pose : turned.poses) {
    CenterAccumulator::Result& camera = pose.camera_centroids;
    camera.centers = relabel(camera.centers, permutation);
    camera.counts = permuted(camera.counts, permutation);
    camera.spread = permuted(camera.spread, permutation);
  }
  if (!fit_poses(turned, params, source_range)) return false;
  turned.notes.insert(turned.notes.begin(), result.notes.begin(), result.notes.end());
  result = std::move(turned);
  return true;
}

}  // namespace l2s::detail
