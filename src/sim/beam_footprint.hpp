#pragma once
// The echo of one laser firing whose footprint may cover several surfaces.
// The footprint (exit diameter plus divergence) is sampled by sub-rays on a
// sunflower pattern with Gaussian power weights (1/e^2 at the rim). Each
// sub-ray's echo carries power ~ weight * reflectivity * cos(incidence) / r^2;
// echoes closer than the range resolution merge into one at their
// power-weighted mean range (a return between the surfaces), each merged echo
// fluctuates (speckle), and the return mode picks the reported one.

#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/ray_caster.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace l2s::sim::detail {

/// What a firing reports; surface == None for no return.
struct Echo {
  double range = 0.0;  ///< [m] along the beam from its origin
  float intensity = 0.0f;
  SurfaceId surface = SurfaceId::None;  ///< of the strongest part of the echo
};

/// Calibrated reflectivity (0..255, like Velodyne's) of a surface.
double lidar_reflectivity(SurfaceId surface);
/// The intensity a sensor reports for a full-footprint hit.
float lidar_intensity(SurfaceId surface, double cos_incidence);

/// Echo of the single centre ray (the ideal lidar), or no return outside
/// [min_range, max_range].
Echo ray_echo(const Hit& hit, const Eigen::Vector3d& direction, double min_range, double max_range);

class BeamFootprint {
 public:
  struct Params {
    int rays = 24;                  ///< sub-rays per footprint, 7..256
    double min_share = 0.05;        ///< an echo needs this share of the footprint's power weight, (0, 1)
    double echo_jitter = 0.25;      ///< relative sigma of an echo's power (speckle), 0..2
    ReturnMode mode = ReturnMode::Strongest;
  };
  BeamFootprint(const BeamOptics& optics, Params params);

  /// The widening cone that holds every sub-ray.
  const Cone& cone() const { return cone_; }

  /// The echo of a beam starting at `origin` along `direction` (camera body
  /// frame; `left` and `up` span its cross-section); `jitter_bits` seeds the
  /// speckle of this firing.
  Echo fire(const RayCaster& caster, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
            const Eigen::Vector3d& left, const Eigen::Vector3d& up, double min_range, double max_range,
            std::uint64_t jitter_bits) const;

 private:
  struct SubRay {
    double s, q;    ///< position in the unit disc: along `left`, along `up`
    double weight;  ///< share of the beam's power, sums to 1
  };
  BeamOptics optics_;
  Params params_;
  Cone cone_;
  std::vector<SubRay> rays_;
};

}  // namespace l2s::sim::detail
