#pragma once
// Registration of labelled hole centroids: translation-only least squares,
// then the full rigid transform (paper Sec. III-D).

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>

#include <Eigen/Geometry>
#include <array>
#include <string>

namespace l2s {

/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT Registrar {
 public:
  struct Params {
    double min_extent = 0.01;     ///< [m] both point sets must spread at least this far from their mean, > 0
    double min_planarity = 0.05;  ///< second/first singular value of the centred points; below = collinear, (0, 1)

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  struct Result {
    bool found = false;          ///< a transform was estimated
    std::string reason;          ///< why not, when !found
    Eigen::Isometry3d T_lidar_camera = Eigen::Isometry3d::Identity();  ///< p_lidar = T * p_camera
    Eigen::Vector3d translation_only = Eigen::Vector3d::Zero();  ///< [m] t' of the first step
    std::array<double, 4> residuals{};  ///< [m] |p_lidar - T p_camera| per hole (enum Hole order)
    double rms = 0.0;            ///< [m] rms of the residuals
  };

  // `Stage(Params = {})` does not compile with GCC while Params has default
  // member initializers (they are parsed only once the outer class is complete).
  Registrar() : Registrar(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit Registrar(Params params);
  const Params& params() const { return params_; }

  /// `lidar` and `camera`: centroids in their sensor frames, labelled alike.
  Result estimate(const HoleCenters& lidar, const HoleCenters& camera) const;

 private:
  Params params_;
};

}  // namespace l2s
