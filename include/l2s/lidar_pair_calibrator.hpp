#pragma once
// The lidar-to-lidar facade (issue 9, "Lidar to lidar"): the lidar branch of
// the paper's pipeline (Sec. III-B) runs on both lidars of every frame, each
// with its own detector (ring lidars sweep by sweep, ring-free ones
// accumulated over a window of sweeps), and the two centre streams go through
// the same pose grouping, per-pose accumulation and joint registration as the
// stereo Calibrator's, giving T_lidar_lidar2 (p_lidar = T * p_lidar2). Both
// sensors being lidars, each also fits the board plane precisely; the centre
// fit is then refined with the two lidars' board normals and offsets of every
// pose (the centres of a ring lidar are biased per pose by where its rings
// cross the holes, which leaves roll and pitch weakest).
//
// Thread safety: as Calibrator (one thread at a time per instance; separate
// instances share nothing).

#include <l2s/calibrator.hpp>
#include <l2s/export.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace l2s {

/// Diagnostics of one frame: the lidar branch of each lidar.
struct LidarPairFrameReport {
  std::string id;        ///< frame name (file stem)
  BranchReport lidar;    ///< the reference lidar (the `lidar/` folder)
  BranchReport lidar2;   ///< the second lidar (`lidar2/`)
  double milliseconds = 0.0;  ///< [ms] wall time of add()
  bool used() const { return lidar.found && lidar2.found; }
};

/// One board pose: a static stretch of frames and each lidar's clustered centres.
struct LidarPairPoseReport {
  int first_frame = 0;       ///< index of its first frame among those added
  int last_frame = 0;        ///< index of its last frame (inclusive)
  std::vector<int> frames;   ///< frames whose centres it accumulated
  CenterAccumulator::Result lidar_centroids;   ///< [m] lidar frame
  CenterAccumulator::Result lidar2_centroids;  ///< [m] lidar2 frame
  bool used = false;         ///< in the joint fit
  std::string reason;        ///< why not, when !used
  double rms = 0.0;          ///< [m] residual rms of its centres under the result (NaN when they did not cluster)
};

class L2S_EXPORT LidarPairCalibrator {
 public:
  /// The lidar side of Calibrator::Params serves both lidars: pass-through,
  /// plane, edges, circles, verifier, ring_free_frames, accumulator,
  /// registrar, poses and joint. Its camera and check fields are not used.
  using Params = Calibrator::Params;

  /// A cheap scene-level sanity check of the result: how well the two
  /// lidars' centres agree under it, pose by pose.
  struct Check {
    CalibrationCheck::Verdict verdict = CalibrationCheck::Verdict::Failed;
    std::vector<std::string> reasons;  ///< why not ok, in words
    double max_pose_rms = 0.0;         ///< [m] largest residual rms of a used pose
  };

  struct Result {
    bool found = false;   ///< T_lidar_lidar2 is valid
    std::string reason;   ///< why not, when !found
    Eigen::Isometry3d T_lidar_lidar2 = Eigen::Isometry3d::Identity();  ///< p_lidar = T * p_lidar2
    int frames_added = 0;   ///< frames given to add()
    int lidar_frames = 0;   ///< detections of the lidar (a ring-free lidar: one per window)
    int lidar2_frames = 0;  ///< detections of lidar2
    std::vector<LidarPairFrameReport> frames;  ///< per-frame diagnostics, in order
    std::vector<LidarPairPoseReport> poses;    ///< board poses found in the frames
    std::vector<int> moving_frames;            ///< frames with centres taken while the board moved
    Registrar::Result registration;  ///< residuals of the centres under T_lidar_lidar2 (rms per hole over the used poses)
    /// The joint fit of the centres alone, before the board planes refine it:
    /// its uncertainty, leave-one-pose-out shifts and suggestion describe
    /// that fit (an upper bound: the planes pin roll, pitch and the
    /// translation along the board normals far better).
    JointRegistrar::Result joint;
    std::vector<std::string> notes;            ///< what the calibrator decided on its own
    Check check;                               ///< the sanity check (failed when not found)
    double lidar_ms = 0.0;   ///< [ms] total lidar branch time
    double lidar2_ms = 0.0;  ///< [ms] total lidar2 branch time
    int poses_used() const;
  };

  /// Throws ParamError naming the field for invalid params or target.
  explicit LidarPairCalibrator(Target target, Params params = Params::preset("default"));
  ~LidarPairCalibrator();
  LidarPairCalibrator(LidarPairCalibrator&&) noexcept;
  LidarPairCalibrator& operator=(LidarPairCalibrator&&) noexcept;

  /// Runs one frame (a sweep of each lidar) through both lidar branches. A
  /// sweep without `ring` gets rings from its elevations or is ring-free
  /// (accumulated, as in Calibrator::add). Bad sweeps are reported in the
  /// frame's branch, never thrown.
  LidarPairFrameReport add(const LidarCloud& lidar, const LidarCloud& lidar2, const std::string& id = "");

  /// Registration of everything added so far (a ring-free window left
  /// incomplete is detected as it stands), with its sanity check.
  Result result() const;

  /// Forgets every frame.
  void reset();

  const Params& params() const;
  const Target& target() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace l2s
