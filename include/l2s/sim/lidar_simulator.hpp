#pragma once
// Simulates one sweep of a spinning multi-beam lidar by casting each beam of
// the model's table at every azimuth step, with a random azimuth offset per
// sweep and Gaussian range noise N(0, (K * 0.008 m)^2) along each ray.

#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace l2s::sim {

class LidarSimulator {
 public:
  struct Params {
    double noise_factor = 1.0;       ///< K: range sigma = K * model.range_sigma0, >= 0
    std::uint64_t seed = 1;          ///< with the frame index, selects offset and noise
    bool random_azimuth_offset = true;  ///< start each sweep at U(0, azimuth_step)
    int threads = 0;                 ///< worker threads, 0 = hardware concurrency
  };

  // Two constructors, not a default argument: GCC cannot use a nested struct's
  // member initialisers in a default argument of its enclosing class.
  explicit LidarSimulator(LidarModel model);
  LidarSimulator(LidarModel model, Params params);

  /// One sweep in the lidar frame (x forward, y left, z up), ordered by
  /// azimuth, then ring. Rays that hit nothing in range give no point.
  /// `surfaces`, when given, receives the surface of each point (for tests).
  LidarCloud sweep(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar,
                   std::uint64_t frame, std::vector<SurfaceId>* surfaces = nullptr) const;

  /// [rad] the azimuth of the first firing of sweep `frame`, in [0, step).
  double azimuth_offset(std::uint64_t frame) const;

  /// Intensity reported for a hit on `surface` at incidence cosine `cos_incidence`.
  static float intensity(SurfaceId surface, double cos_incidence);

  const LidarModel& model() const { return model_; }

 private:
  LidarModel model_;
  Params params_;
};

}  // namespace l2s::sim
