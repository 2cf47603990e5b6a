#pragma once
// The per-laser model of ring recovery. A spinning lidar's laser k fires from
// an origin a few centimetres (VLP-16) to a few decimetres (HDL-64E) off the
// sensor origin, so its returns lie on z = d * tan(theta_k) + h_k, with d the
// horizontal distance. Divided by d that is a line in (u, v) = (1/d, z/d):
//   v = t_k + h_k * u,   t_k = tan(theta_k).
// Far returns (u ~ 0) sit at v = t_k whatever h_k is; near ones move by h_k/d.
// Noise along the beam (range noise) moves a return along its line, so the
// residual v - t_k - h_k u measures only the elevation error.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace l2s::io::fan {

/// A return in model coordinates.
struct Point {
  double u = 0.0;  ///< [1/m] 1 / horizontal distance
  double v = 0.0;  ///< z / horizontal distance (tangent of the elevation seen from the origin)
};

/// Least-squares sums of the points given to one line, with a Gaussian prior
/// on h (ridge): a line seen at one distance only keeps the prior's offset.
struct LineSums {
  double n = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0;
  double u_min = 1e300, u_max = -1e300;
  void add(const Point& p) {
    n += 1;
    u_min = std::min(u_min, p.u);
    u_max = std::max(u_max, p.u);
    su += p.u;
    sv += p.v;
    suu += p.u * p.u;
    suv += p.u * p.v;
    svv += p.v * p.v;
  }
  void add(const LineSums& o) {
    n += o.n;
    su += o.su;
    sv += o.sv;
    suu += o.suu;
    suv += o.suv;
    svv += o.svv;
    u_min = std::min(u_min, o.u_min);
    u_max = std::max(u_max, o.u_max);
  }
};

/// One laser: v = t + h u.
struct Line {
  double t = 0.0;      ///< tan(elevation)
  double h = 0.0;      ///< [m] vertical origin offset
  double scale = 0.0;  ///< residual scale (rms, floored at the noise floor), v units
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();  ///< of (t, h) per unit residual variance
  double u_low = 0.0;                             ///< [1/m] range of u of its points
  double u_high = 0.0;
  std::size_t count = 0;  ///< points in the last fit

  double predict(double u) const { return t + h * u; }
  /// Standard deviation of a new return at u about the prediction (noise and
  /// the uncertainty of t and h), v units.
  double sigma(double u) const { return std::sqrt(variance(u)); }
  /// sigma(u) squared (no square root: it runs once per return and line).
  double variance(double u) const {
    const double var = cov(0, 0) + 2.0 * cov(0, 1) * u + cov(1, 1) * u * u;
    return scale * scale * (1.0 + std::max(0.0, var));
  }
  double elevation() const { return std::atan(t); }  ///< [rad]
};

/// Fits t and h to `sums` with a prior h ~ N(h_prior, prior_sigma^2) weighed
/// against residuals of the expected size `noise` (v units), which also steadies
/// the residual scale of a line with few returns; `floor` bounds the scale.
Line fit_line(const LineSums& sums, double h_prior, double prior_sigma, double noise, double floor);

/// v-units per radian of elevation at tangent t: dv/dtheta = 1 + t^2.
inline double v_per_radian(double t) { return 1.0 + t * t; }

}  // namespace l2s::io::fan
