#pragma once
// The four hole centres from edge points on the board plane (paper Sec. III-C:
// circles of known radius by sample consensus in the plane, checked against the
// known hole spacing), optionally refined as one rigid pattern with the board's
// thickness modelled.

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// Finds and labels the four holes of the board among edge points.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT CircleFinder {
 public:
  struct Params {
    double inlier_threshold = 0.02;   ///< [m] | |q - c| - r | for a point to support a circle, > 0
    int min_circle_points = 3;        ///< fewest points on a circle candidate (paper: 3), >= 2
    int max_iterations = 2000;        ///< point pairs tried; every pair when there are fewer, >= 1
    int max_candidates = 16;          ///< circle candidates kept (best first), >= 4; dense lidars need more (default preset: 32)
    double spacing_tolerance = 0.03;  ///< [m] max distance of a centre from the fitted rigid pattern, > 0
    bool project_along_rays = true;   ///< move points onto the plane along their viewing ray (false: orthogonally, paper)
    bool joint_fit = true;            ///< refine the four holes as one rigid pattern (false: independent circles, paper)
    bool model_thickness = true;      ///< fit the aperture a ray sees through a thick board (false: thin board, paper)
    bool fit_radius = true;           ///< joint fit: estimate the holes' apparent radius (one for all four; the spacing stays exact), so the centres do not slide when holes look smaller than target.yaml says (lidar beam footprint)
    int max_refine_iterations = 30;   ///< Gauss-Newton iterations of each fit, >= 1
    /// Joint fit with gradients: when no four candidates form the pattern (or
    /// two sets do), find the pattern as a whole by votes of every rim for its
    /// placement; clutter outvotes single holes far more easily than the
    /// pattern (false: candidates only, paper)
    bool pattern_votes = true;
    std::uint64_t seed = 7;           ///< random pairs when there are too many to try them all

    void validate() const;  ///< throws ParamError naming the field
    static Params paper();  ///< independent circles, orthogonal projection, thin board, fixed radius
  };

  struct Result {
    bool found = false;
    std::string reason;                   ///< why the frame was rejected; empty on success
    HoleCenters centers;                  ///< [m] sensor frame, on the plane, indexed by enum Hole
    std::vector<Circle> candidates;       ///< every circle candidate, best first (sensor frame)
    std::vector<std::size_t> candidate_points;  ///< supporting points of each candidate
    std::array<int, 4> matched{{-1, -1, -1, -1}};  ///< candidate index of each hole
    double pattern_angle = 0.0;           ///< [rad] in-plane roll of the hole pattern (0 = upright)
    double rms = 0.0;                     ///< [m] rms residual of the final fit
    double radius = 0.0;                  ///< [m] apparent hole radius of the final fit (target's radius unless fit_radius)
    std::size_t fit_points = 0;           ///< points used in the final fit
    bool by_pattern_votes = false;        ///< found by the pattern's votes, not by four candidates
  };

  // Two constructors rather than `Params params = {}`: a nested struct's default
  // member initialisers are not usable in a default argument of its enclosing class.
  CircleFinder();
  explicit CircleFinder(Params params);

  /// `edges`: edge points in the sensor frame, whose origin is the sensor (each
  /// point's viewing ray is its direction); `plane`: the board plane (either
  /// normal sign); `up`: the sensor's up axis (lidar +z, camera optical -y);
  /// `gradients`: optional, one per edge: the direction (in the plane, sensor
  /// frame) in which the image intensity changes there. With them, circle
  /// candidates come from gradient votes (robust to a textured board),
  /// otherwise from pairs of points (sparse lidar edges). Bad data (a plane
  /// that is not finite, too few edges, non-finite points) is a reason in
  /// the result; throws ParamError for an invalid target, an `up` that is not
  /// a finite non-zero vector, or `gradients` of another length than `edges`.
  Result find(const std::vector<Eigen::Vector3d>& edges, const Plane& plane, const Eigen::Vector3d& up,
              const Target& target = Target{}, const std::vector<Eigen::Vector3d>& gradients = {}) const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace l2s
