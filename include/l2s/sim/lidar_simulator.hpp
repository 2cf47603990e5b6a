#pragma once
// Simulates one sweep of a lidar. A spinning lidar casts each beam of its
// table at every azimuth step, with a random azimuth offset per sweep; a
// rosette lidar fires one frame period of its non-repetitive pattern, frame
// after frame. The range gets Gaussian noise N(0, (K * sigma0)^2) along the
// beam. The ideal lidar of the paper casts one exact ray per firing from the
// sensor origin; a model with a laser table (LidarModel::corrections) fires
// each laser from its own origin and angles, and with `beam_footprint` the
// beam's divergence mixes the echoes of every surface it touches.

#include <l2s/export.hpp>
#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

namespace l2s::sim {

namespace detail {
class BeamFootprint;
}

class L2S_SIM_EXPORT LidarSimulator {
 public:
  struct Params {
    double noise_factor = 1.0;       ///< K: range sigma = K * model.range_sigma0, >= 0
    std::uint64_t seed = 1;          ///< with the frame index, selects offset and noise
    bool random_azimuth_offset = true;  ///< spinning: start each sweep at U(0, azimuth_step)
    int threads = 0;                 ///< worker threads, 0 = hardware concurrency
    bool nan_for_no_return = false;  ///< keep firings without return as NaN points (organised output)

    // Beam footprint (the model's BeamOptics); off: one exact ray per firing.
    bool beam_footprint = false;     ///< sample the footprint where the beam nears an outline
    ReturnMode return_mode = ReturnMode::Strongest;  ///< which of several echoes is reported
    int footprint_rays = 24;         ///< sub-rays per footprint, 7..256
    double min_return_share = 0.05;  ///< an echo needs this share of the beam's power weight, (0, 1)
    double echo_jitter = 0.25;       ///< relative sigma of each echo's power (speckle), 0..2
  };

  // Two constructors, not a default argument: GCC cannot use a nested struct's
  // member initialisers in a default argument of its enclosing class.
  explicit LidarSimulator(LidarModel model);
  LidarSimulator(LidarModel model, Params params);
  ~LidarSimulator();
  LidarSimulator(LidarSimulator&&) noexcept;
  LidarSimulator& operator=(LidarSimulator&&) noexcept;

  /// One sweep (spinning) or frame (rosette) in the lidar frame (x forward,
  /// y left, z up). Spinning: ordered by azimuth, then ring, with `ring` set.
  /// Rosette: in firing order, `ring` empty. Firings without a return in
  /// range give no point (or NaN, see Params). `surfaces`, when given,
  /// receives the surface of each point (for tests; None for NaN points).
  LidarCloud sweep(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar,
                   std::uint64_t frame, std::vector<SurfaceId>* surfaces = nullptr) const;

  /// Firings per sweep or frame (returns or not).
  int firings_per_sweep() const;

  /// Unit direction of every firing of sweep `frame` in the lidar frame, in
  /// the order of the sweep's slots (spinning: azimuth, then ring).
  std::vector<Eigen::Vector3d> firing_directions(std::uint64_t frame) const;

  /// [rad] spinning: the azimuth of the first firing of sweep `frame`, in [0, step).
  double azimuth_offset(std::uint64_t frame) const;

  /// Intensity reported for a hit on `surface` at incidence cosine `cos_incidence`.
  static float intensity(SurfaceId surface, double cos_incidence);

  const LidarModel& model() const { return model_; }
  const Params& params() const { return params_; }

 private:
  struct Slot;
  struct Beam;
  void fire(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar, const Beam& beam,
            std::uint64_t noise_bits, Slot* slot) const;
  std::vector<Slot> spinning_slots(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar,
                                   std::uint64_t frame) const;
  std::vector<Slot> rosette_slots(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar,
                                  std::uint64_t frame) const;

  LidarModel model_;
  Params params_;
  std::unique_ptr<detail::BeamFootprint> footprint_;  ///< when params_.beam_footprint
};

}  // namespace l2s::sim
