// Ridge least squares for one laser's line v = t + h u (see laser_line.hpp).
#include "lidar/rings/laser_line.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace l2s::io::fan {

Line fit_line(const LineSums& s, double h_prior, double prior_sigma, double noise, double floor) {
  // Minimises sum (v - t - h u)^2 / noise^2 + (h - h_prior)^2 / prior_sigma^2.
  const double lambda = (noise * noise) / (prior_sigma * prior_sigma);
  Eigen::Matrix2d A;
  A << s.n, s.su, s.su, s.suu + lambda;
  const Eigen::Vector2d b(s.sv, s.suv + lambda * h_prior);
  Line line;
  line.cov = A.inverse();
  const Eigen::Vector2d x = line.cov * b;
  line.t = x[0];
  line.h = x[1];
  const double rss = s.svv - 2.0 * line.t * s.sv - 2.0 * line.h * s.suv + line.t * line.t * s.n +
                     2.0 * line.t * line.h * s.su + line.h * line.h * s.suu;
  // The prior pins h, so about one parameter is free; kPriorWeight pseudo-returns
  // at the expected noise keep the scale of a line with few returns sane.
  constexpr double kPriorWeight = 4.0;
  const double dof = std::max(0.0, s.n - 1.0);
  line.scale = std::max(
      floor, std::sqrt((std::max(0.0, rss) + kPriorWeight * noise * noise) / (dof + kPriorWeight)));
  line.count = static_cast<std::size_t>(s.n);
  line.u_low = s.u_min;
  line.u_high = s.u_max;
  return line;
}

}  // namespace l2s::io::fan
