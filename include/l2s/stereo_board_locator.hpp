#pragma once
// Where the board may be in a stereo pair, found at low resolution before any
// full-resolution matching. Matching the whole frame at full resolution over
// the whole working range costs pixels x disparities; the board covers a
// fraction of the image and of the depth range. A coarse pass over the
// working range finds the board-sized planes; the camera branch then matches
// each one's region, and only its depth band, at full resolution.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/pass_through_filter.hpp>
#include <l2s/plane_segmenter.hpp>
#include <l2s/stereo_matcher.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <string>
#include <vector>

namespace l2s {

/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT StereoBoardLocator {
 public:
  struct Params {
    double coarse_width = 480.0;  ///< [px] the coarse pass matches the pair scaled to about this width, >= 160
    double min_board_px = 48.0;   ///< [px] ... but keeps the board's short side at least this long at max_depth, > 0
    /// Every n-th coarse cell in x and y becomes a point: the segmentation's
    /// cost follows the points (2 saves ~25 ms on a 1280x960 pair), but a
    /// small board loses its plane (a 640x480 wide-angle rig did), >= 1
    int coarse_stride = 1;
    PlaneSegmenter::Params plane = coarse_plane();  ///< board candidates in the coarse cloud (thresholds for its coarser depth)
    double region_margin = 0.15;  ///< [m] each region is the candidate's extent plus this on every side, >= 0
    double depth_margin = 0.15;   ///< [m] and its depth band the candidate's depths plus this each way, > 0

    static PlaneSegmenter::Params coarse_plane();  ///< the stereo segmenter with thresholds for coarse depth
    void validate() const;                         ///< throws ParamError naming the field
  };

  /// A place where the board may be: a board-sized plane of the coarse cloud.
  struct Region {
    int candidate = -1;        ///< index into Result::plane.candidates
    PixelRect roi;             ///< [px] left-image region to match at full resolution
    double min_depth = 0.0;    ///< [m] depth band to search there
    double max_depth = 0.0;    ///< [m]
  };

  struct Result {
    bool found = false;              ///< at least one region
    std::string reason;              ///< why none, when !found
    double scale = 1.0;              ///< scale of the coarse pass
    StereoMatcher::Result stereo;    ///< the coarse pass
    PassThroughFilter::Result pass_through;  ///< indices into stereo.cloud
    StereoCloud cloud;               ///< the coarse cloud after pass-through: what `plane` indexes
    PlaneSegmenter::Result plane;    ///< candidates of the coarse cloud
    std::vector<Region> regions;     ///< one per plausible candidate, most board-like first
  };

  // Two constructors rather than `Params params = {}` (see PlaneSegmenter).
  StereoBoardLocator();
  explicit StereoBoardLocator(Params params);
  const Params& params() const { return params_; }

  /// Rectified pair. `stereo`: the full-resolution matcher the regions are for
  /// (its depth range is the working range searched here, its other settings
  /// are used at the coarse scale); `pass_through`: the camera's box and range.
  /// Throws InputError naming the image when one is unusable (empty,
  /// not 1 or 3 channels) or its size differs from the other's or its camera's.
  Result locate(const Image& left, const Image& right, const StereoCamera& cameras, const Target& target,
                const StereoMatcher::Params& stereo, const PassThroughFilter::Params& pass_through) const;

  /// The coarse pass alone: the whole frame's disparity and, after
  /// pass-through, its cloud, at the scale locate() works at; no candidates
  /// (found stays false). For a caller that knows where the board is (its
  /// markers gave it) and wants the frame's depth only. Arguments and throws
  /// as locate().
  Result match_coarse(const Image& left, const Image& right, const StereoCamera& cameras, const Target& target,
                      const StereoMatcher::Params& stereo, const PassThroughFilter::Params& pass_through) const;

 private:
  Params params_;
};

}  // namespace l2s
