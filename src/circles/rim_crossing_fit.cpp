#include "circles/rim_crossing_fit.hpp"

#include "circles/circle_fit.hpp"

#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace l2s::detail {
namespace {

using Vector4 = Eigen::Matrix<double, 4, 1>;
using Matrix4 = Eigen::Matrix<double, 4, 4>;

/// Coordinates in the board plane: origin and two orthonormal axes in it.
struct PlaneFrame {
  Eigen::Vector3d origin, u, v, normal;

  Eigen::Vector2d to_plane(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - origin;
    return {d.dot(u), d.dot(v)};
  }
  Eigen::Vector3d to_sensor(const Eigen::Vector2d& q) const {
    return origin + q.x() * u + q.y() * v;
  }
};

PlaneFrame plane_frame(const HoleCenters& start, const Plane& plane) {
  PlaneFrame f;
  f.normal = plane.normal();
  const Eigen::Vector3d centroid = 0.25 * (start[0] + start[1] + start[2] + start[3]);
  f.origin = plane.projection(centroid);
  const Eigen::Vector3d across = (start[1] - start[0]) + (start[3] - start[2]);  // TL->TR, BL->BR
  f.u = (across - across.dot(f.normal) * f.normal).normalized();
  f.v = f.normal.cross(f.u);
  return f;
}

/// The target's hole pattern laid onto the start centres (in-plane, labels as
/// given) by the 2D rigid motion that fits them best, reflections allowed
/// (the plane frame's handedness is arbitrary); the rms misfit in `rms`.
std::array<Eigen::Vector2d, 4> snap_pattern(const std::array<Eigen::Vector2d, 4>& start,
                                            const Target& target, double* rms) {
  const std::array<Eigen::Vector2d, 4> model = target.hole_centers();
  Eigen::Vector2d ms = Eigen::Vector2d::Zero(), mm = Eigen::Vector2d::Zero();
  for (int h = 0; h < 4; ++h) ms += 0.25 * start[h], mm += 0.25 * model[h];
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
  for (int h = 0; h < 4; ++h) C += (start[h] - ms) * (model[h] - mm).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix2d R =
      svd.matrixU() * svd.matrixV().transpose();  // may reflect: that is wanted
  std::array<Eigen::Vector2d, 4> out;
  double sum = 0.0;
  for (int h = 0; h < 4; ++h) {
    out[h] = ms + R * (model[h] - mm);
    sum += (out[h] - start[h]).squaredNorm();
  }
  *rms = std::sqrt(sum / 4.0);
  return out;
}

/// One crossing in plane coordinates, with the hole it belongs to.
struct Interval {
  Eigen::Vector2d board, hole, mid;
  Eigen::Vector2d through;  ///< in-plane shift of the ray from the front face to the back face
  int index = 0;            ///< which hole
};

/// The pattern: hole h at t + R(theta) m_h, radius r; x = (tx, ty, theta, r).
struct Pattern {
  std::array<Eigen::Vector2d, 4> model;  ///< about the pattern's centroid
  Eigen::Vector2d centroid;

  Eigen::Vector2d centre(const Vector4& x, int h) const {
    const double c = std::cos(x(2)), s = std::sin(x(2));
    const Eigen::Vector2d& m = model[h];
    return centroid + Eigen::Vector2d(x(0) + c * m.x() - s * m.y(), x(1) + s * m.x() + c * m.y());
  }
};

/// The ray through an in-plane point as the circle fit sees an edge point:
/// where it leaves the board (the back rim) is the same circle shifted.
EdgePoint2 ray_at(const Eigen::Vector2d& q, const Interval& iv, bool thick) {
  return EdgePoint2{q, thick ? iv.through : Eigen::Vector2d::Zero()};
}

/// Signed distance of an in-plane point from the aperture a ray through it
/// sees (positive on the board: aperture_residual) and its gradient in x.
double aperture_distance(const Pattern& pattern, const Vector4& x, const Interval& iv,
                         const Eigen::Vector2d& q, bool thick, Vector4* gradient) {
  const Eigen::Vector2d c = pattern.centre(x, iv.index);
  const EdgePoint2 ray = ray_at(q, iv, thick);
  const Eigen::Vector2d front = ray.q - c, back = ray.q + ray.shift - c;
  const Eigen::Vector2d d = back.norm() > front.norm() ? back : front;  // the rim that bounds the aperture
  const double length = d.norm();
  if (length < 1e-12) {
    gradient->setZero();
  } else {
    const Eigen::Vector2d n = d / length;
    const Eigen::Vector2d arm = c - pattern.centroid - x.head<2>();  // d c / d theta = J arm
    (*gradient) << -n.x(), -n.y(), -(n.x() * -arm.y() + n.y() * arm.x()), -1.0;
  }
  return aperture_residual(ray, c, x(3));
}

struct Solution {
  Vector4 x;
  std::vector<double> violation;  ///< per interval, [m]
};

Solution solve(const Pattern& pattern, const std::vector<Interval>& intervals,
               const std::vector<bool>& used, Vector4 x, const RimCrossingFitParams& params) {
  Solution out;
  for (int k = 0; k < params.iterations; ++k) {
    Matrix4 H = Matrix4::Zero();
    Vector4 g = Vector4::Zero();
    const auto add = [&](double r, const Vector4& J, double w) {
      H += w * J * J.transpose();
      g += w * J * r;
    };
    for (std::size_t i = 0; i < intervals.size(); ++i) {
      if (!used[i]) continue;
      const Interval& iv = intervals[i];
      Vector4 J;
      const double board = aperture_distance(pattern, x, iv, iv.board, params.model_thickness, &J);
      if (board < 0.0) add(board, J, 1.0);  // a board return inside the aperture
      const double hole = aperture_distance(pattern, x, iv, iv.hole, params.model_thickness, &J);
      if (hole > 0.0) add(hole, J, 1.0);  // a ray through the hole on the board
      add(aperture_distance(pattern, x, iv, iv.mid, params.model_thickness, &J), J,
          params.midpoint_weight);
    }
    if (!params.fit_radius) H(3, 3) += 1e12;  // pins the radius
    const Eigen::LDLT<Matrix4> ldlt(H + 1e-12 * Matrix4::Identity());
    const Vector4 step = -ldlt.solve(g);
    if (!step.allFinite()) break;
    x += step;
    if (step.head<2>().norm() < 1e-9 && std::abs(step(2)) < 1e-9 && std::abs(step(3)) < 1e-9) break;
  }
  out.x = x;
  for (const Interval& iv : intervals) {
    const Eigen::Vector2d c = pattern.centre(x, iv.index);
    const double board = aperture_residual(ray_at(iv.board, iv, params.model_thickness), c, x(3));
    const double hole = aperture_residual(ray_at(iv.hole, iv, params.model_thickness), c, x(3));
    out.violation.push_back(std::max({0.0, -board, hole}));
  }
  return out;
}

}  // namespace

RimCrossingFit fit_pattern_to_rim_crossings(const HoleCenters& start, const Plane& plane,
                                            const std::vector<RimCrossing>& crossings,
                                            const Target& target,
                                            const RimCrossingFitParams& params) {
  RimCrossingFit fit;
  const PlaneFrame frame = plane_frame(start, plane);
  std::array<Eigen::Vector2d, 4> start_2d;
  for (int h = 0; h < 4; ++h) start_2d[h] = frame.to_plane(start[h]);
  double snap_rms = 0.0;
  Pattern pattern;
  const std::array<Eigen::Vector2d, 4> snapped = snap_pattern(start_2d, target, &snap_rms);
  if (!(snap_rms < params.max_shift)) {
    fit.reason = "the centres are not the target's pattern";
    return fit;
  }
  pattern.centroid = 0.25 * (snapped[0] + snapped[1] + snapped[2] + snapped[3]);
  for (int h = 0; h < 4; ++h) pattern.model[h] = snapped[h] - pattern.centroid;

  // Each crossing to the hole whose rim its midpoint lies nearest.
  std::vector<Interval> intervals;
  std::array<int, 4> per_hole{};
  for (const RimCrossing& c : crossings) {
    Interval iv;
    iv.board = frame.to_plane(c.board_side);
    iv.hole = frame.to_plane(c.hole_side);
    iv.mid = 0.5 * (iv.board + iv.hole);
    double nearest = std::numeric_limits<double>::infinity();
    for (int h = 0; h < 4; ++h) {
      const double off = std::abs((iv.mid - snapped[h]).norm() - target.hole_radius);
      if (off < nearest) nearest = off, iv.index = h;
    }
    if (!(nearest < target.hole_radius * 0.5)) continue;  // not at a rim of the pattern
    const Eigen::Vector3d ray = (0.5 * (c.board_side + c.hole_side)).normalized();
    const double along = std::abs(ray.dot(frame.normal));
    if (along < 0.1) continue;  // grazing: the interval says little
    const Eigen::Vector3d in_plane = ray - ray.dot(frame.normal) * frame.normal;
    iv.through = Eigen::Vector2d(in_plane.dot(frame.u), in_plane.dot(frame.v)) *
                 target.board_thickness / along;
    ++per_hole[iv.index];
    intervals.push_back(iv);
  }
  const int holes_seen = static_cast<int>(
      std::count_if(per_hole.begin(), per_hole.end(), [](int n) { return n > 0; }));
  if (static_cast<int>(intervals.size()) < params.min_crossings || holes_seen < 3) {
    std::ostringstream why;
    why << intervals.size() << " rim crossings on " << holes_seen << " holes (need "
        << params.min_crossings << " on 3)";
    fit.reason = why.str();
    return fit;
  }

  Vector4 x(0.0, 0.0, 0.0, target.hole_radius);
  std::vector<bool> used(intervals.size(), true);
  Solution solution = solve(pattern, intervals, used, x, params);
  // A mixed return or a stray one makes an interval no rim can satisfy:
  // leave such crossings out and fit again.
  int dropped = 0;
  for (std::size_t i = 0; i < intervals.size(); ++i)
    if (solution.violation[i] > params.max_violation) used[i] = false, ++dropped;
  if (dropped > 0) solution = solve(pattern, intervals, used, solution.x, params);

  fit.crossings = static_cast<int>(intervals.size()) - dropped;
  fit.radius = solution.x(3);
  HoleCenters centers;
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector2d c = pattern.centre(solution.x, h);
    if (!((c - start_2d[h]).norm() < params.max_shift)) {
      fit.reason = "the fit moved a hole centre by more than " +
                   std::to_string(params.max_shift * 1e3) + " mm";
      return fit;
    }
    centers[h] = frame.to_sensor(c);
  }
  if (!(fit.radius > 0.7 * target.hole_radius && fit.radius < 1.1 * target.hole_radius)) {
    fit.reason = "the fitted hole radius is implausible";
    return fit;
  }
  fit.centers = centers;
  return fit;
}

}  // namespace l2s::detail
