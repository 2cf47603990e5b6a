#pragma once
// The Calibrator facade: streams frames through the lidar and camera branches
// of the paper's pipeline (Sec. III), accumulates the hole centres and
// registers them into T_lidar_camera. Frames are added one at a time, so a
// calibration can run live; result() is available at any point.
//
// Thread safety: one Calibrator is not safe to share; add(), reset() and
// result() of the same instance need one thread at a time (or a lock).
// Separate instances share nothing and may run in parallel threads.
// camera_branch() is const and may run concurrently with itself and with
// add() on one instance (it reads only the cameras, target and params;
// `l2s calibrate` runs the next frames' camera branches so).

#include <l2s/board_pose_refiner.hpp>
#include <l2s/board_verifier.hpp>
#include <l2s/calibration_check.hpp>
#include <l2s/camera.hpp>
#include <l2s/center_accumulator.hpp>
#include <l2s/circle_finder.hpp>
#include <l2s/discontinuity_filter.hpp>
#include <l2s/occupancy_edge_filter.hpp>
#include <l2s/edge_filter.hpp>
#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/joint_registrar.hpp>
#include <l2s/mono_board_detector.hpp>
#include <l2s/pass_through_filter.hpp>
#include <l2s/plane_segmenter.hpp>
#include <l2s/pose_grouper.hpp>
#include <l2s/registrar.hpp>
#include <l2s/scene_observer.hpp>
#include <l2s/stereo_board_locator.hpp>
#include <l2s/stereo_matcher.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace l2s {

/// What one sensor's branch made of one frame.
struct BranchReport {
  bool found = false;        ///< four labelled hole centres were found
  std::string failed_stage;  ///< stage that stopped the branch ("plane", "edges", "circles", ...)
  std::string reason;        ///< why, in words; empty on success
  HoleCenters centers{};     ///< [m] sensor frame, enum Hole order (valid when found)
  std::size_t input_points = 0;   ///< points after the pass-through filter
  std::size_t plane_inliers = 0;  ///< board-plane points
  std::size_t edge_points = 0;    ///< edge points given to the circle finder
  double fit_rms = 0.0;           ///< [m] rms of the circle finder's rim fit (both branches)
  double rim_rms_px = 0.0;        ///< [px] camera: rms of the rim refinement whose centres were kept; 0 when not refined
  double hole_radius = 0.0;       ///< [m] apparent hole radius of the rim fit (real lidars see holes smaller than they are)
  /// The target's ArUco markers found in the (left) image, where their pose
  /// labelled the holes (mono; stereo: the markers' pose kept, or the stereo
  /// board's where the two agreed); 0 where the labels come from the image's up.
  int markers = 0;
  /// Mono: where each marker found lies on the board (MonoBoardDetector::Result::placements).
  std::vector<MonoBoardDetector::MarkerPlacement> marker_placements;
  int hypotheses = 0;             ///< board-sized planes verified before one was kept (or all failed)
  std::string note;               ///< non-fatal remark (e.g. refinement fell back to the circle fit)
  /// Lidar: the board plane its centres lie on (sensor frame, normal towards
  /// the sensor), valid when found; it rests on every board return, far more
  /// than the holes' edges do.
  std::optional<Plane> board_plane;
  /// Ring lidars: where its rings crossed the hole rims (sensor frame, on
  /// board_plane), one per hole edge; a pose's crossings pin its holes
  /// more sharply than the frames' centres do (Params::fit_lidar_rim_crossings).
  std::vector<RimCrossing> rim_crossings;
  double milliseconds = 0.0;      ///< [ms] wall time of the branch
  /// What the calibration check needs of the pair: set by
  /// Calibrator::camera_branch() (so add(lidar, camera) can check), kept by
  /// add() only for the frames it checks. Its image edges, the costly part,
  /// are measured by add() from check_left, only for those frames.
  std::shared_ptr<const CameraObservation> observation;
  /// The left image the check measures edges in (rectified when the
  /// dataset's images are raw); set with observation, dropped by add().
  std::shared_ptr<const Image> check_left;
};

/// Diagnostics of one frame: both branches.
struct FrameReport {
  std::string id;        ///< frame name (file stem)
  BranchReport lidar;
  BranchReport camera;
  double milliseconds = 0.0;  ///< [ms] wall time of add()
  bool used() const { return lidar.found && camera.found; }
};

/// One board pose of a calibration: a static stretch of frames (PoseGrouper),
/// its centres clustered per sensor, and its part in the joint fit.
struct PoseReport {
  int first_frame = 0;   ///< index of its first frame among those added
  int last_frame = 0;    ///< index of its last frame (inclusive)
  std::vector<int> frames;  ///< frames whose centres it accumulated (outliers within first..last left out)
  /// Frames of `frames` whose lidar (camera) detection the pose's centres left
  /// out: elsewhere than that sensor's consensus over the pose, or outside its
  /// centres' clusters. Wrong detections; the scene check ignores their board.
  std::vector<int> lidar_outlier_frames, camera_outlier_frames;
  CenterAccumulator::Result lidar_centroids;   ///< clustered lidar centres of the pose
  CenterAccumulator::Result camera_centroids;  ///< clustered camera centres of the pose
  bool used = false;     ///< in the joint fit
  std::string reason;    ///< why not, when !used (centres do not cluster, rejected as an outlier)
  double rms = 0.0;      ///< [m] residual rms of its centres under the result (NaN when they did not cluster)
  std::optional<Plane> lidar_plane;  ///< mean board plane of its lidar detections (normal towards the lidar)
  /// Its lidar centres are the pattern fitted to its rings' rim crossings
  /// (Params::fit_lidar_rim_crossings), not the clustered frames' centres.
  bool lidar_rims_fitted = false;
  /// That fit's apparent hole radius over the target's (0 when not fitted):
  /// below 1, the beam's footprint mixes board and hole at the rims, and
  /// where a ring seems to leave the board depends on the echo's energy.
  double lidar_rim_radius_ratio = 0.0;
};

/// The lidar side of one static board pose whose returns were accumulated
/// over seconds into one cloud (a solid-state lidar as many users keep it;
/// DATASET.md `lidar: accumulated`): detected once by
/// Calibrator::detect_accumulated, then given to add() with every image frame
/// of that pose, whose camera centres its centres pair with. Cheap to copy
/// (shared, immutable).
class L2S_EXPORT AccumulatedLidar {
 public:
  /// The cloud's detection (found, centres, or why not); empty until made
  /// by detect_accumulated().
  const BranchReport& report() const;
  bool ring_free() const;  ///< the cloud went the ring-free way

 private:
  friend class Calibrator;
  struct State;
  std::shared_ptr<const State> state_;
};

/// The facade: one per rig and calibration run (see thread safety above).
class L2S_EXPORT Calibrator {
 public:
  /// Every stage's parameters in one place (loaded from / saved to YAML by
  /// io::load_calibrator_params / io::save_calibrator_params).
  /// Which path a lidar sweep takes. Auto: its returns decide
  /// (io::classify_scan): a ring field that gives the scan lines, or lines
  /// recovered from the elevations, go the ring way; a scan without lines
  /// (solid-state, accumulated) the ring-free way. Rings or RingFree force one.
  enum class LidarScan { Auto, Rings, RingFree };

  struct Params {
    /// The "default" preset: Params{} and preset("default") are the same.
    Params();

    // Lidar branch: pass-through, plane, discontinuities, circles.
    PassThroughFilter::Params lidar_pass_through;
    PlaneSegmenter::Params lidar_plane = PlaneSegmenter::Params::lidar();
    DiscontinuityFilter::Params discontinuity;
    OccupancyEdgeFilter::Params occupancy;  ///< hole edges of ring-free (accumulated) clouds
    LidarScan lidar_scan = LidarScan::Auto;  ///< the lidar path: auto (the returns decide), rings or ring_free (forced)
    int ring_free_frames = 20;  ///< ring-free lidars: sweeps of the static board accumulated into one detection (2 s at 10 Hz); a window without the board grows, detected again every ring_free_frames / 2 more, up to twice this (a sparse scan), >= 1
    CircleFinder::Params lidar_circles;
    BoardVerifier::Params lidar_verifier;  ///< which board-sized plane is the board (holes seen through, outline clear)
    // Camera branch: stereo, pass-through, plane, Sobel edges, circles, rim refinement.
    StereoMatcher::Params stereo;  ///< full-resolution matching; its depth range is the working range of the camera branch
    PassThroughFilter::Params camera_pass_through;
    bool locate_board = true;  ///< find the board at low resolution first, then match only its region and depth band (false: one full-frame pass, as the paper)
    StereoBoardLocator::Params locator;  ///< the coarse pass (locate_board)
    PlaneSegmenter::Params camera_plane = PlaneSegmenter::Params::stereo();  ///< full-frame candidates; with locate_board, its inlier_threshold bounds the board points of a region
    EdgeFilter::Params edges;
    CircleFinder::Params camera_circles;
    BoardVerifier::Params camera_verifier;
    bool refine_camera_pose = true;  ///< fit the board pose to the hole rims in both images
    /// A target with markers: the pose their corners give in both images,
    /// refined on the rims where those converge, is the board's first
    /// hypothesis, kept where no hole is seen covered; where the stereo
    /// search finds the board elsewhere, the markers win, and the report's
    /// note says so. It is the only one where SGM cannot tell a printed face
    /// from its surroundings (false: the stereo search alone, as the paper)
    bool board_from_markers = true;
    BoardPoseRefiner::Params board_refiner;
    // Mono camera (lidar-mono): the board by its ArUco markers, refined with the rims.
    MonoBoardDetector::Params mono;
    // Accumulation and registration.
    CenterAccumulator::Params accumulator;  ///< its min_frames: fewest frames with centres on each side for a result
    Registrar::Params registrar;
    PoseGrouper::Params poses;  ///< how frames are grouped into board poses (the board static within each)
    JointRegistrar::Params joint;  ///< the fit over all poses: outlying poses, when to suggest another
    /// [px] The error of the image distance a camera measures a board
    /// pose's range by (stereo: the rims' disparity; mono: the markers'
    /// spread), shared by every frame of the pose: its depth errs by this
    /// times range^2 / (fx B) and the board tilts by that over the hole
    /// pattern. Widens the result's uncertainty with range, >= 0.
    double camera_range_bias_px = 0.02;
    /// With two or more used poses, refine the centre fit with each pose's
    /// board planes (the lidar's from all its board returns, the camera's
    /// through its centres): a ring lidar's centres carry a bias per pose
    /// from where its rings cross the holes, its board plane does not.
    bool refine_with_board_planes = true;
    /// Ring lidars: fit each pose's hole pattern to every place its rings
    /// crossed a rim, in all the pose's sweeps, keeping each rim inside the
    /// azimuth step it was crossed in (not only near the step's middle).
    bool fit_lidar_rim_crossings = true;
    bool parallel_branches = true;  ///< run the lidar and camera branches of a frame concurrently
    // The scene-level check of the result (calibration_check.hpp).
    bool check_result = true;  ///< result() checks the transform against the scene and fills Result::quality
    int check_frames = 8;      ///< frames kept for the check, evenly spread over the frames used (between this and twice this are held; while fewer used frames came, frames without the board on both sides fill up to as many again), >= 1
    SceneObserver::Params observer;   ///< what is kept of each checked frame
    CalibrationCheck::Params check;   ///< scoring and verdict thresholds
    /// A checked result is at best suspect when its own 95 % bounds
    /// (joint.uncertainty; the norm of the three translations, of the three
    /// rotations) exceed these: the scene may agree with it, yet the data
    /// pin it no better (a far board with little stereo depth resolution
    /// turns the camera about the board unseen), > 0.
    double trusted_bound_translation = 0.1;   ///< [m]
    double trusted_bound_rotation_deg = 2.0;  ///< [deg]

    /// "default" (the most accurate) or "paper" (the 2017 method's values);
    /// throws ParamError for any other name.
    static Params preset(const std::string& name);
    /// Throws ParamError naming the first invalid field (e.g. "lidar_plane.max_angle").
    void validate() const;
  };

  struct Result {
    bool found = false;   ///< T_lidar_camera is valid
    std::string reason;   ///< why not, when !found
    Eigen::Isometry3d T_lidar_camera = Eigen::Isometry3d::Identity();  ///< p_lidar = T * p_camera
    int frames_added = 0;     ///< frames given to add()
    int lidar_frames = 0;     ///< frames whose lidar branch found four centres
    int camera_frames = 0;    ///< frames whose camera branch found four centres
    CenterAccumulator::Result lidar_centroids;   ///< clustered lidar centres
    CenterAccumulator::Result camera_centroids;  ///< clustered camera centres
    Registrar::Result registration;              ///< residuals of the fit
    std::vector<FrameReport> frames;             ///< per-frame diagnostics, in order
    double lidar_ms = 0.0;   ///< [ms] total lidar branch time
    double camera_ms = 0.0;  ///< [ms] total camera branch time
    /// The scene-level check of T_lidar_camera (params.check_result): verdict
    /// ok / suspect / failed with reasons. Failed when the transform was not found.
    CalibrationCheck::Report quality;
    bool checked = false;    ///< quality holds a check (check_result and a transform found)
    /// [deg] The camera's hole labels were turned by this before the fit,
    /// because the scene supports that fit clearly better than the labels as
    /// the sensors gave them (a rig rolled against the lidar); 0: as given.
    int labels_turned = 0;
    std::vector<std::string> notes;  ///< what the calibrator decided on its own (e.g. turned labels), in words
    /// Mono: where each marker lies on the board, the median over the
    /// frames that placed it (`placed`: in three frames or more;
    /// `left_out`: in most of them). A marker off its place by more than
    /// its frames' scatter explains, and by more than 1.5 mm, is in `notes`
    /// with its offset, so that target.yaml's `markers: centres` can be
    /// corrected.
    std::vector<MonoBoardDetector::MarkerPlacement> marker_placements;
    /// Board poses found in the frames (one for a static board). With
    /// several, lidar_centroids and camera_centroids are those of the first
    /// used pose, and `registration` holds the joint fit (its residuals: rms
    /// per hole over the used poses).
    std::vector<PoseReport> poses;
    std::vector<int> moving_frames;  ///< frames with centres taken while the board moved (in no pose)
    /// The joint fit over the used poses: per-DoF uncertainty, the
    /// leave-one-pose-out shifts (two or more poses) and, when poorly
    /// conditioned, the kind of pose that would help most.
    JointRegistrar::Result joint;
    int poses_used() const;  ///< poses in the joint fit
  };

  /// Throws ParamError naming the field for invalid params, target or
  /// cameras (image size or fx, fy not positive, P not finite, or a stereo
  /// baseline -P_right[0][3] / fx_right that is not positive).
  Calibrator(StereoCamera cameras, Target target, Params params = Params::preset("default"));
  /// Lidar-mono (DATASET.md v2): the camera side is one camera, which finds
  /// the board by the ArUco markers of `target` (MonoBoardDetector); frames
  /// come through add(lidar, left). Accumulation and registration are the
  /// stereo path's. The scene check uses the left image's edges and the
  /// markers' board pose (no stereo depth), and weighs no relabelled
  /// alternatives: the markers fix the camera's hole labels. Throws
  /// ParamError as above, and for a target without markers.
  Calibrator(CameraInfo camera, ImageKind images, Target target, Params params = Params::preset("default"));
  ~Calibrator();
  Calibrator(Calibrator&&) noexcept;
  Calibrator& operator=(Calibrator&&) noexcept;

  /// Runs one frame through both branches and accumulates what they found.
  /// A cloud without `ring` gets rings from elevation angles; a ring-free
  /// cloud (non-repetitive scan) is accumulated with the next ones, and every
  /// ring_free_frames sweeps give one lidar detection (the frame that
  /// completes the window reports it; the others report "accumulating", as
  /// do the frames of a window without the board that grows (up to twice
  /// ring_free_frames) to be detected again; a window left incomplete is
  /// detected as it stands by result()).
  /// Bad sweeps (empty, NaN, no board, ring or intensity of another length
  /// than the points) are reported in the frame's lidar branch, never thrown.
  /// Images that cannot be used throw InputError naming the image ("left
  /// image: ...") before any work starts: empty, not 1 or 3 channels, pixels
  /// that do not fill the image, or a size other than the cameras'.
  FrameReport add(const LidarCloud& lidar, const Image& left, const Image& right,
                  const std::string& id = "");

  /// Lidar-mono: one frame of the lidar and the one camera (a calibrator
  /// built with a CameraInfo). Throws InputError for an unusable image, or
  /// ("right image: ...") on a stereo calibrator.
  FrameReport add(const LidarCloud& lidar, const Image& left, const std::string& id = "");

  /// The mono camera's branch alone (see camera_branch(left, right)).
  BranchReport camera_branch(const Image& left) const;

  /// Built for one camera (lidar-mono)?
  bool mono() const;

  /// The camera branch of add() alone, accumulating nothing. Its report can be
  /// given to add(lidar, camera) of every calibrator with the same cameras,
  /// target and camera-side params (one per lidar model, say), so the stereo
  /// work of a frame is done once, or run ahead on another thread. Same
  /// exceptions as add(); add(lidar, camera_branch(left, right)) gives what
  /// add(lidar, left, right) gives.
  BranchReport camera_branch(const Image& left, const Image& right) const;

  /// add() with the camera branch already run by camera_branch(); only the
  /// lidar branch runs here. The frame's milliseconds include the camera's.
  FrameReport add(const LidarCloud& lidar, const BranchReport& camera, const std::string& id = "");

  /// Detects an accumulated cloud of one static board pose once, as it
  /// stands (a ring-free one is a whole window already; its path is chosen
  /// as for a sweep, Params::lidar_scan). Accumulates nothing: give the
  /// result to add() with each image frame of the pose. Bad clouds are
  /// reported in its report(), never thrown.
  AccumulatedLidar detect_accumulated(const LidarCloud& cloud) const;
  /// add() for a frame of an accumulated cloud's pose: the cloud's centres
  /// (found once) pair with this frame's camera; its detection time counts
  /// with the first frame that gives it. Throws as add(lidar, ...), and
  /// InputError for an AccumulatedLidar not made by detect_accumulated().
  FrameReport add(const AccumulatedLidar& lidar, const Image& left, const Image& right, const std::string& id = "");
  FrameReport add(const AccumulatedLidar& lidar, const Image& left, const std::string& id = "");  ///< lidar-mono
  FrameReport add(const AccumulatedLidar& lidar, const BranchReport& camera, const std::string& id = "");

  /// Registration of everything accumulated so far, checked against the
  /// scene (params.check_result). When the scene clearly supports the fit
  /// with the camera's labels turned by a symmetry of the target, that fit
  /// is returned and Result::labels_turned says so; when it cannot tell, the
  /// verdict is failed ("ambiguous").
  Result result() const;

  /// The frames kept for the check (CheckFrame, evenly spread over the used
  /// frames, and while those are few, over the frames without the board on
  /// both sides too), to check any other transform with CalibrationCheck.
  const std::vector<CheckFrame>& check_frames() const;

  /// Forgets every frame.
  void reset();

  const Params& params() const;
  const StereoCamera& cameras() const;
  const Target& target() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace l2s
