#include <l2s/target.hpp>

#include <l2s/error.hpp>

#include <cmath>

namespace l2s {

const char* hole_name(Hole hole) {
  switch (hole) {
    case Hole::TopLeft: return "TL";
    case Hole::TopRight: return "TR";
    case Hole::BottomLeft: return "BL";
    case Hole::BottomRight: return "BR";
  }
  return "?";
}

Target Target::paper2017() {
  Target target;
  target.board_width = 1.2;
  target.board_height = 0.8;
  target.board_thickness = 0.02;
  target.hole_radius = 0.12;
  target.hole_spacing_x = 0.3;
  target.hole_spacing_y = 0.3;
  return target;
}

Target Target::preset(const std::string& name) {
  if (name == "default") return Target{};
  if (name == "paper2017") return paper2017();
  throw ParamError("board", "unknown preset '" + name + "' (expected default or paper2017)");
}

std::array<Eigen::Vector2d, 4> Target::hole_centers() const {
  const double hx = hole_spacing_x / 2.0;
  const double hy = hole_spacing_y / 2.0;
  return {Eigen::Vector2d(-hx, hy), Eigen::Vector2d(hx, hy), Eigen::Vector2d(-hx, -hy),
          Eigen::Vector2d(hx, -hy)};
}

void Target::validate() const {
  const auto require_positive = [](double value, const char* field) {
    if (!(value > 0.0) || !std::isfinite(value)) throw ParamError(field, "must be a positive length");
  };
  require_positive(board_width, "board_width");
  require_positive(board_height, "board_height");
  require_positive(board_thickness, "board_thickness");
  require_positive(hole_radius, "hole_radius");
  require_positive(hole_spacing_x, "hole_spacing_x");
  require_positive(hole_spacing_y, "hole_spacing_y");
  if (hole_spacing_x <= 2.0 * hole_radius)
    throw ParamError("hole_spacing_x", "holes overlap (spacing must exceed the hole diameter)");
  if (hole_spacing_y <= 2.0 * hole_radius)
    throw ParamError("hole_spacing_y", "holes overlap (spacing must exceed the hole diameter)");
  if (hole_spacing_x / 2.0 + hole_radius >= board_width / 2.0)
    throw ParamError("board_width", "holes reach past the left/right board edges");
  if (hole_spacing_y / 2.0 + hole_radius >= board_height / 2.0)
    throw ParamError("board_height", "holes reach past the top/bottom board edges");
}

}  // namespace l2s
