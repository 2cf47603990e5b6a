// Pattern completion for the occupancy edge filter (see the header).
#include "lidar/hole_completion.hpp"

#include <cmath>

namespace l2s::detail {
namespace {

Eigen::Vector2d perpendicular(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }

Eigen::Vector2d rotated(const Eigen::Vector2d& d, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * d.x() - s * d.y(), s * d.x() + c * d.y()};
}

/// `a`-`b` is a side of the rectangle: the opposite side lies `across` away, on either side.
void add_across(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double across,
                std::vector<Eigen::Vector2d>* out) {
  const Eigen::Vector2d n = perpendicular((b - a).normalized());
  for (const double side : {-1.0, 1.0}) {
    out->push_back(a + side * across * n);
    out->push_back(b + side * across * n);
  }
}

/// `a`-`b` is a diagonal of the sx x sy rectangle: its other corners, in either mirror image.
void add_diagonal(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double sx, double sy,
                  std::vector<Eigen::Vector2d>* out) {
  const Eigen::Vector2d w = b - a;
  const double angle = std::atan2(sy, sx);  // between the diagonal and the x side
  for (const double mirror : {-1.0, 1.0}) {
    const Eigen::Vector2d side_x = sx * rotated(w.normalized(), mirror * angle);
    out->push_back(a + side_x);
    out->push_back(b - side_x);
  }
}

}  // namespace

std::vector<Eigen::Vector2d> predicted_holes(const std::vector<Eigen::Vector2d>& found,
                                             double spacing_x, double spacing_y, double tolerance) {
  std::vector<Eigen::Vector2d> out;
  const double diagonal = std::hypot(spacing_x, spacing_y);
  for (std::size_t i = 0; i < found.size(); ++i)
    for (std::size_t j = i + 1; j < found.size(); ++j) {
      const double d = (found[j] - found[i]).norm();
      if (std::abs(d - spacing_x) < tolerance) add_across(found[i], found[j], spacing_y, &out);
      if (std::abs(d - spacing_y) < tolerance) add_across(found[i], found[j], spacing_x, &out);
      if (std::abs(d - diagonal) < tolerance)
        add_diagonal(found[i], found[j], spacing_x, spacing_y, &out);
    }
  return out;
}

}  // namespace l2s::detail
