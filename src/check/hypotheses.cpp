// The transforms a four-centre fit cannot tell from the right one: the hole
// labels of one sensor turned by a symmetry of the pattern (hole_symmetry.hpp).

#include <l2s/calibration_check.hpp>

#include <cmath>
#include <string>

namespace l2s {
namespace {

std::string turned_name(int degrees) { return "camera labels turned " + std::to_string(degrees) + " deg"; }

}  // namespace

std::vector<CalibrationCheck::Alternative> relabelled_alternatives(const HoleCenters& lidar, const HoleCenters& camera,
                                                                   const Target& target, const Registrar& registrar) {
  std::vector<CalibrationCheck::Alternative> out;
  for (const HoleSymmetry& turn : hole_symmetries(target)) {
    if (turn.degrees == 0) continue;
    const Registrar::Result fit = registrar.estimate(lidar, relabel(camera, turn.permutation));
    if (!fit.found) continue;
    CalibrationCheck::Alternative alternative;
    alternative.name = turned_name(turn.degrees);
    alternative.degrees = turn.degrees;
    alternative.relabel = turn.permutation;
    alternative.T_lidar_camera = fit.T_lidar_camera;
    alternative.residual_rms = fit.rms;
    out.push_back(alternative);
  }
  return out;
}

// Relabelled camera centres c'[h] = c[perm[h]] sit where the turn S (about
// the board normal through its centre) moves c[h]; the fit T' with
// T' S c = T c is T * S^-1.
std::vector<CalibrationCheck::Alternative> board_alternatives(const Eigen::Isometry3d& T_lidar_camera,
                                                              const Eigen::Isometry3d& T_camera_board,
                                                              const Target& target) {
  std::vector<CalibrationCheck::Alternative> out;
  for (const HoleSymmetry& turn : hole_symmetries(target)) {
    if (turn.degrees == 0) continue;
    const Eigen::Isometry3d unturn(Eigen::AngleAxisd(-turn.degrees * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
    CalibrationCheck::Alternative alternative;
    alternative.name = turned_name(turn.degrees);
    alternative.degrees = turn.degrees;
    alternative.relabel = turn.permutation;
    alternative.T_lidar_camera = T_lidar_camera * T_camera_board * unturn * T_camera_board.inverse();
    out.push_back(alternative);
  }
  return out;
}

}  // namespace l2s
