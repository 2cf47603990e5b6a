// Quarter turns of the four-hole pattern as relabellings: the hole at board
// position p appears, to a sensor that sees the board turned by theta, where
// R(theta) p is, and is labelled by that place.

#include <l2s/hole_symmetry.hpp>

#include <Eigen/Geometry>
#include <cmath>

namespace l2s {
namespace {

/// The turn by `degrees` of the pattern whose hole centres are `holes`;
/// false when some hole lands farther than `tolerance` from every hole.
bool turn_of(const std::array<Eigen::Vector2d, 4>& holes, int degrees, double tolerance, HoleSymmetry& out) {
  const Eigen::Rotation2Dd turn(degrees * M_PI / 180.0);
  out.degrees = degrees;
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector2d moved = turn * holes[h];
    int nearest = -1;
    for (int k = 0; k < 4; ++k)
      if ((holes[k] - moved).norm() <= tolerance) nearest = k;
    if (nearest < 0) return false;
    out.permutation[h] = nearest;
  }
  return true;
}

}  // namespace

std::vector<HoleSymmetry> quarter_turns() {
  Target square;
  square.hole_spacing_x = square.hole_spacing_y = 1.0;
  std::vector<HoleSymmetry> turns;
  for (const int degrees : {0, 90, 180, 270}) {
    HoleSymmetry turn;
    if (turn_of(square.hole_centers(), degrees, 1e-6, turn)) turns.push_back(turn);
  }
  return turns;
}

std::vector<HoleSymmetry> hole_symmetries(const Target& target, double tolerance) {
  std::vector<HoleSymmetry> turns;
  for (const int degrees : {0, 90, 180, 270}) {
    HoleSymmetry turn;
    if (turn_of(target.hole_centers(), degrees, tolerance, turn)) turns.push_back(turn);
  }
  return turns;
}

HoleCenters relabel(const HoleCenters& centers, const HolePermutation& permutation) {
  HoleCenters out;
  for (int h = 0; h < 4; ++h) out[h] = centers[permutation[h]];
  return out;
}

}  // namespace l2s
