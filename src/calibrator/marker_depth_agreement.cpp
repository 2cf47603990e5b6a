#include "calibrator/marker_depth_agreement.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace l2s::detail {
namespace {

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

/// On the board's face: inside its outline and clear of every hole, both by `margin`.
bool on_face(const Eigen::Vector2d& q, const Target& target, double margin) {
  if (std::abs(q.x()) > 0.5 * target.board_width - margin || std::abs(q.y()) > 0.5 * target.board_height - margin)
    return false;
  for (const Eigen::Vector2d& hole : target.hole_centers())
    if ((q - hole).norm() < target.hole_radius + margin) return false;
  return true;
}

}  // namespace

MarkerDepthAgreement marker_depth_agreement(const StereoCloud& cloud, const Eigen::Isometry3d& T_camera_board,
                                            const Target& target, double max_tilt_deg, int min_points,
                                            double margin) {
  MarkerDepthAgreement out;
  const Eigen::Vector3d normal = T_camera_board.linear().col(2);
  const Eigen::Vector3d centre = T_camera_board.translation();
  const Eigen::Isometry3d T_board_camera = T_camera_board.inverse();
  // Each point against the board's face where its viewing ray meets it: the
  // depth the disparity gave beside the depth the markers' pose gives.
  std::vector<Eigen::Vector3d> face;
  std::vector<double> residuals;
  for (const Eigen::Vector3d& p : cloud.points) {
    const double along = normal.dot(p);
    if (std::abs(along) < 1e-9) continue;
    const Eigen::Vector3d hit = p * (normal.dot(centre) / along);
    if (hit.z() <= 0.0) continue;
    if (!on_face((T_board_camera * hit).head<2>(), target, margin)) continue;
    face.push_back(p);
    residuals.push_back(p.z() - hit.z());
  }
  out.face_points = static_cast<int>(face.size());
  char line[200];
  if (out.face_points < min_points) {
    std::snprintf(line, sizeof line, "%d coarse stereo points on the markers' board (%d needed)", out.face_points,
                  min_points);
    out.summary = line;
    return out;
  }
  // Mismatched cells (a plain face, repeated texture) fall far off the rest;
  // within a quarter of a hole radius a point can not move the holes.
  const double mid = median(residuals);
  std::vector<double> spread(residuals.size());
  for (std::size_t i = 0; i < residuals.size(); ++i) spread[i] = std::abs(residuals[i] - mid);
  const double keep = std::max(3.0 * 1.4826 * median(spread), 0.25 * target.hole_radius);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int kept = 0;
  for (std::size_t i = 0; i < face.size(); ++i)
    if (std::abs(residuals[i] - mid) <= keep) mean += face[i], ++kept;
  mean /= kept;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < face.size(); ++i)
    if (std::abs(residuals[i] - mid) <= keep) scatter += (face[i] - mean) * (face[i] - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Eigen::Vector3d fitted = solver.eigenvectors().col(0);
  out.tilt_deg = std::acos(std::min(1.0, std::abs(fitted.dot(normal)))) * 180.0 / M_PI;
  out.offset = std::abs(fitted.dot(centre - mean));
  out.agrees = kept >= min_points && out.tilt_deg <= max_tilt_deg && out.offset <= 0.5 * target.hole_radius;
  std::snprintf(line, sizeof line, "the coarse stereo depth on the markers' board (%d points) is tilted %.1f deg "
                "and %.0f mm off it", kept, out.tilt_deg, out.offset * 1e3);
  out.summary = line;
  return out;
}

}  // namespace l2s::detail
