#pragma once
// Groups a time-ordered stream of board observations into board poses: the
// board stands still within a pose and moves between poses (issue 9, "Several
// poses"). Works on any number of observation streams per frame (lidar,
// stereo camera, a mono camera or a second lidar): a frame belongs to the
// current pose when a stream that saw the board in it agrees, within a
// tolerance, with the pose's first view from that stream (a move of the board
// moves it for every sensor; one sensor alone disagreeing made a wrong
// detection). Within a pose, each stream's views are then sorted by consensus.

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>

#include <optional>
#include <string>
#include <vector>

namespace l2s {

/// One frame: the four labelled hole centres each stream found, in that
/// stream's sensor frame; std::nullopt where a stream did not find the board.
using FrameCenters = std::vector<std::optional<HoleCenters>>;

/// Thread safety: immutable after construction; group() may run concurrently.
class L2S_EXPORT PoseGrouper {
 public:
  struct Params {
    /// [m] mean hole distance (any quarter turn of the labels) beyond which
    /// the board has moved; above the per-frame centre noise, below the
    /// smallest deliberate move, > 0
    double tolerance = 0.05;
    /// Fewest frames of a static stretch that make a pose, >= 1. A stretch
    /// with fewer is the board in motion (unless it is the only stretch).
    int min_frames = 3;

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  /// One board pose: a static stretch of frames.
  struct Pose {
    int first = 0;               ///< index of its first frame
    int last = 0;                ///< index of its last frame (inclusive)
    std::vector<int> frames;     ///< frames that agree with the pose (within first..last)
    std::vector<int> outliers;   ///< frames within first..last that disagree (a bad detection, not a move)
    /// Per stream: frames of `frames` whose view from that stream lies
    /// elsewhere than the stream's consensus over the pose (a wrong detection
    /// of that sensor while another sensor agrees with the pose); their
    /// views of that stream are not to be used.
    std::vector<std::vector<int>> stream_outliers;
  };

  struct Result {
    std::vector<Pose> poses;     ///< in time order
    std::vector<int> moving;     ///< frames with a detection outside every pose: the board was moving
    std::vector<int> empty;      ///< frames where no stream saw the board
    /// A line per skipped stretch, e.g. "frames 10-11: board moving (2 frames, need 3 for a pose)".
    std::vector<std::string> notes;
  };

  PoseGrouper() : PoseGrouper(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit PoseGrouper(Params params);
  const Params& params() const { return params_; }

  /// Groups `frames` (time order; every frame has the same number of streams,
  /// else InputError). Never throws on bad data: NaN centres count as not found.
  /// `stream_names` name the streams in the notes ("lidar", "camera"; default "stream k").
  Result group(const std::vector<FrameCenters>& frames, const std::vector<std::string>& stream_names = {}) const;

 private:
  Params params_;
};

/// [m] Mean distance between the holes of `a` and `b` under the quarter turn
/// of `b`'s labels that brings them closest (labels may flip between frames
/// on a sensor rolled near 90 deg); +inf when fewer than two holes are finite.
L2S_EXPORT double pattern_distance(const HoleCenters& a, const HoleCenters& b);

}  // namespace l2s
