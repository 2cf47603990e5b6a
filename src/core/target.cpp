#include <l2s/target.hpp>

#include <l2s/error.hpp>

#include <algorithm>
#include <cmath>
#include <set>

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

namespace {

struct Dictionary {
  const char* name;
  int bits;
  int size;
};

// OpenCV's predefined ArUco dictionaries (the names of cv::aruco::PREDEFINED_DICTIONARY_NAME).
constexpr Dictionary kDictionaries[] = {
    {"DICT_4X4_50", 4, 50},     {"DICT_4X4_100", 4, 100},   {"DICT_4X4_250", 4, 250},
    {"DICT_4X4_1000", 4, 1000}, {"DICT_5X5_50", 5, 50},     {"DICT_5X5_100", 5, 100},
    {"DICT_5X5_250", 5, 250},   {"DICT_5X5_1000", 5, 1000}, {"DICT_6X6_50", 6, 50},
    {"DICT_6X6_100", 6, 100},   {"DICT_6X6_250", 6, 250},   {"DICT_6X6_1000", 6, 1000},
    {"DICT_7X7_50", 7, 50},     {"DICT_7X7_100", 7, 100},   {"DICT_7X7_250", 7, 250},
    {"DICT_7X7_1000", 7, 1000}, {"DICT_ARUCO_ORIGINAL", 5, 1024}};

const Dictionary* find_dictionary(const std::string& name) {
  for (const Dictionary& d : kDictionaries)
    if (name == d.name) return &d;
  return nullptr;
}

/// Distance from point p to the axis-aligned square of half side h around c (0 inside).
double distance_to_square(const Eigen::Vector2d& p, const Eigen::Vector2d& c, double h) {
  const Eigen::Vector2d d = ((p - c).cwiseAbs().array() - h).max(0.0).matrix();
  return d.norm();
}

void validate_markers(const Target& target, const MarkerLayout& m) {
  if (!find_dictionary(m.dictionary))
    throw ParamError("markers.dictionary", "unknown ArUco dictionary '" + m.dictionary + "' (e.g. DICT_6X6_250)");
  if (!(m.size > 0.0) || !std::isfinite(m.size)) throw ParamError("markers.size", "must be a positive length");
  if (m.ids.empty()) throw ParamError("markers.ids", "at least one marker is needed");
  if (m.centres.size() != m.ids.size())
    throw ParamError("markers.centres", "one centre per id is needed (" + std::to_string(m.ids.size()) + " ids, " +
                                            std::to_string(m.centres.size()) + " centres)");
  const int count = MarkerLayout::dictionary_size(m.dictionary);
  if (std::set<int>(m.ids.begin(), m.ids.end()).size() != m.ids.size())
    throw ParamError("markers.ids", "ids must be unique");
  for (int id : m.ids)
    if (id < 0 || id >= count)
      throw ParamError("markers.ids", "id " + std::to_string(id) + " is not in " + m.dictionary + " (0.." +
                                          std::to_string(count - 1) + ")");
  const double h = 0.5 * m.size;
  const auto holes = target.hole_centers();
  for (std::size_t i = 0; i < m.centres.size(); ++i) {
    const Eigen::Vector2d& c = m.centres[i];
    const std::string which = "marker " + std::to_string(m.ids[i]);
    if (!c.allFinite()) throw ParamError("markers.centres", which + ": not a finite position");
    if (std::abs(c.x()) + h > 0.5 * target.board_width || std::abs(c.y()) + h > 0.5 * target.board_height)
      throw ParamError("markers.centres", which + " reaches past the board's edges");
    for (const Eigen::Vector2d& hole : holes)
      if (distance_to_square(hole, c, h) < target.hole_radius)
        throw ParamError("markers.centres", which + " lies over a hole");
    for (std::size_t j = 0; j < i; ++j)
      if ((m.centres[j] - c).cwiseAbs().maxCoeff() < m.size)
        throw ParamError("markers.centres", which + " overlaps marker " + std::to_string(m.ids[j]));
  }
}

}  // namespace

MarkerLayout MarkerLayout::corners_default() {
  MarkerLayout layout;
  layout.ids = {1, 2, 3, 4};
  layout.centres = {Eigen::Vector2d(-0.55, 0.35), Eigen::Vector2d(0.55, 0.35), Eigen::Vector2d(-0.55, -0.35),
                    Eigen::Vector2d(0.55, -0.35)};
  return layout;
}

std::array<Eigen::Vector3d, 4> MarkerLayout::corners(std::size_t index) const {
  const Eigen::Vector2d& c = centres.at(index);
  const double h = 0.5 * size;
  return {Eigen::Vector3d(c.x() - h, c.y() + h, 0.0), Eigen::Vector3d(c.x() + h, c.y() + h, 0.0),
          Eigen::Vector3d(c.x() + h, c.y() - h, 0.0), Eigen::Vector3d(c.x() - h, c.y() - h, 0.0)};
}

int MarkerLayout::dictionary_bits(const std::string& name) {
  const Dictionary* d = find_dictionary(name);
  return d ? d->bits : 0;
}

int MarkerLayout::dictionary_size(const std::string& name) {
  const Dictionary* d = find_dictionary(name);
  return d ? d->size : 0;
}

Target Target::with_default_markers() {
  Target target;
  target.markers = MarkerLayout::corners_default();
  return target;
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
  if (name == "markers") return with_default_markers();
  if (name == "paper2017") return paper2017();
  throw ParamError("board", "unknown preset '" + name + "' (expected default, markers or paper2017)");
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
  if (markers) validate_markers(*this, *markers);
}

}  // namespace l2s
