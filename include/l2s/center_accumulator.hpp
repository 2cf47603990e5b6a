#pragma once
// Accumulates the four hole centres over N frames, clusters them and returns
// one centroid per hole (paper Sec. III-C, last paragraph).

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>

#include <array>
#include <string>
#include <vector>

namespace l2s {

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
  };

  // `Stage(Params = {})` does not compile with GCC while Params has default
  // member initializers (they are parsed only once the outer class is complete).
  CenterAccumulator() : CenterAccumulator(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit CenterAccumulator(Params params);
  const Params& params() const { return params_; }

  /// Adds the four labelled centres of one frame; non-finite centres are skipped.
  void add(const HoleCenters& centers);
  /// Clusters what was added so far; never throws on bad data.
  Result estimate() const;
  /// Forgets every frame.
  void reset();
  int frames() const { return frames_; }

 private:
  Params params_;
  int frames_ = 0;
  std::array<std::vector<Eigen::Vector3d>, 4> centers_;
};

/// "TL", "TR", "BL", "BR".
L2S_EXPORT const char* hole_name(Hole hole);

}  // namespace l2s
