#pragma once
// Accumulates the four hole centres over N frames, clusters them and returns
// one centroid per hole (paper Sec. III-C, last paragraph). Each frame's labels
// are first turned to agree with the other frames' (hole_symmetry.hpp): a
// sensor rolled near 90 deg labels by an "up" that flips between frames.

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/hole_symmetry.hpp>

#include <array>
#include <string>
#include <vector>

namespace l2s {

/// Thread safety: add() and reset() need one thread at a time (or a lock);
/// const functions may run concurrently with each other.
class L2S_EXPORT CenterAccumulator {
 public:
  /// How a hole's cluster becomes one point.
  enum class Estimator {
    Mean,             ///< the cluster centroid, as in the paper
    GeometricMedian,  ///< Weiszfeld median of the cluster: an outlier inside the tolerance barely moves it
  };

  struct Params {
    double cluster_tolerance = 0.02;   ///< [m] delta_cluster: Euclidean linkage distance, > 0
    double min_cluster_fraction = 0.5; ///< the hole's cluster needs >= this fraction of the frames, (0, 1]
    double max_cluster_fraction = 1.0; ///< and <= this fraction (more means a hole was counted twice), >= min
    int min_frames = 1;                ///< estimate() fails with fewer frames added, >= 1
    Estimator estimator = Estimator::GeometricMedian;  ///< Mean reproduces the paper exactly
    /// Relabel each frame by the quarter turn of the pattern that brings its
    /// centres nearest to a reference frame (the one most others agree with),
    /// so labels are consistent over frames on any mounting (false: the paper).
    bool align_labels = true;

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  struct Result {
    bool found = false;             ///< all four holes have a valid cluster
    std::string reason;             ///< why not, e.g. "hole TL: largest cluster has 3 of 20 centres"
    HoleCenters centers{};          ///< [m] one per hole, ordered as enum Hole
    std::array<int, 4> counts{};    ///< centres in each hole's chosen cluster
    std::array<double, 4> spread{}; ///< [m] rms distance of the cluster's centres to its estimate
    int frames = 0;                 ///< frames added
    int relabelled_frames = 0;      ///< frames whose labels align_labels turned
    /// Per frame added (in add() order): false when one of its centres lies
    /// outside its hole's chosen cluster, i.e. the estimate left it out.
    std::vector<bool> clustered;
  };

  // `Stage(Params = {})` does not compile with GCC while Params has default
  // member initializers (they are parsed only once the outer class is complete).
  CenterAccumulator() : CenterAccumulator(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit CenterAccumulator(Params params);
  const Params& params() const { return params_; }

  /// Adds the four labelled centres of one frame; non-finite centres are skipped.
  void add(const HoleCenters& centers);
  /// The labels each frame ends up with: the quarter turn applied to frame i
  /// (its index among add() calls) before clustering, identity without align_labels.
  std::vector<HoleSymmetry> frame_turns() const;
  /// Clusters what was added so far; never throws on bad data.
  Result estimate() const;
  /// Forgets every frame.
  void reset();
  int frames() const { return static_cast<int>(frames_.size()); }

 private:
  Params params_;
  std::vector<HoleCenters> frames_;  ///< as added, NaN where a centre was not finite
};

}  // namespace l2s
