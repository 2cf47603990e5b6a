#pragma once
// Pass-through filter (paper Sec. III-A): keeps the part of a cloud where the
// board can be, so that later stages work on a small, relevant set.

#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace l2s {

/// Keeps the finite points inside an axis-aligned box and a range interval,
/// both in the sensor's own frame. Returns indices, so attributes (ring,
/// intensity, pixel) stay reachable.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT PassThroughFilter {
 public:
  struct Params {
    static constexpr double kInf = std::numeric_limits<double>::infinity();
    Eigen::Vector3d min_xyz{-kInf, -kInf, -kInf};  ///< [m] lower box corner, sensor frame; -inf = open
    Eigen::Vector3d max_xyz{kInf, kInf, kInf};     ///< [m] upper box corner, each >= min_xyz
    double min_range = 0.0;                        ///< [m] distance from the sensor origin, >= 0
    double max_range = kInf;                       ///< [m] > min_range; inf = unlimited

    /// Throws ParamError naming the field when the limits are inconsistent.
    void validate() const;
  };

  struct Result {
    std::vector<std::size_t> kept;      ///< indices into the input, ascending
    std::size_t dropped_non_finite = 0;  ///< NaN or inf coordinates
    std::size_t dropped_box = 0;         ///< outside the box
    std::size_t dropped_range = 0;       ///< inside the box but outside [min_range, max_range]
  };

  // Two constructors rather than `Params params = {}`: a nested struct's default
  // member initialisers are not usable in a default argument of its enclosing class.
  PassThroughFilter();
  explicit PassThroughFilter(Params params);

  Result filter(const std::vector<Eigen::Vector3d>& points) const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

/// The points (and ring/intensity, when present) of `cloud` at `indices`, in that order.
L2S_EXPORT LidarCloud select(const LidarCloud& cloud, const std::vector<std::size_t>& indices);

}  // namespace l2s
