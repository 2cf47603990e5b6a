#include <l2s/sim/appearance.hpp>

#include <l2s/error.hpp>

#include <cmath>

namespace l2s::sim {
namespace {

void check_range(double value, double lo, double hi, const char* field, const char* unit = "") {
  if (!(value >= lo && value <= hi))
    throw ParamError(std::string("appearance.") + field,
                     "must be " + std::to_string(lo) + ".." + std::to_string(hi) + unit);
}

}  // namespace

namespace {

constexpr BoardTexture kBoardTextures[] = {BoardTexture::Matte,   BoardTexture::WoodGrain,  BoardTexture::LowContrast,
                                           BoardTexture::Speckle, BoardTexture::NoisePrint, BoardTexture::Chipboard,
                                           BoardTexture::Black,   BoardTexture::White,      BoardTexture::Logo,
                                           BoardTexture::Sticker, BoardTexture::Glossy};
constexpr Background kBackgrounds[] = {Background::Textured, Background::Bricks, Background::Tiles, Background::Plain,
                                       Background::White};

/// "a, b, c" for an error message.
std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

const char* name_of(BoardTexture texture) {
  switch (texture) {
    case BoardTexture::WoodGrain: return "wood";
    case BoardTexture::LowContrast: return "low-contrast";
    case BoardTexture::Speckle: return "speckle";
    case BoardTexture::NoisePrint: return "noise-print";
    case BoardTexture::Chipboard: return "chipboard";
    case BoardTexture::Black: return "black";
    case BoardTexture::White: return "white";
    case BoardTexture::Logo: return "logo";
    case BoardTexture::Sticker: return "sticker";
    case BoardTexture::Glossy: return "glossy";
    case BoardTexture::Matte: break;
  }
  return "matte";
}

const char* name_of(Background background) {
  switch (background) {
    case Background::Bricks: return "bricks";
    case Background::Tiles: return "tiles";
    case Background::Plain: return "plain";
    case Background::White: return "white";
    case Background::Textured: break;
  }
  return "textured";
}

std::vector<std::string> board_texture_names() {
  std::vector<std::string> names;
  for (BoardTexture t : kBoardTextures) names.emplace_back(name_of(t));
  return names;
}

std::vector<std::string> background_names() {
  std::vector<std::string> names;
  for (Background b : kBackgrounds) names.emplace_back(name_of(b));
  return names;
}

const char* name_of(Sky sky) { return sky == Sky::Daylight ? "daylight" : "uniform"; }

BoardTexture board_texture_from_name(const std::string& name, const std::string& field) {
  for (BoardTexture t : kBoardTextures)
    if (name == name_of(t)) return t;
  throw ParamError(field, "unknown board texture '" + name + "' (" + listed(board_texture_names()) + ")");
}

Background background_from_name(const std::string& name, const std::string& field) {
  for (Background b : kBackgrounds)
    if (name == name_of(b)) return b;
  throw ParamError(field, "unknown background '" + name + "' (" + listed(background_names()) + ")");
}

Sky sky_from_name(const std::string& name, const std::string& field) {
  for (Sky s : {Sky::Uniform, Sky::Daylight})
    if (name == name_of(s)) return s;
  throw ParamError(field, "unknown sky '" + name + "' (uniform, daylight)");
}

bool Appearance::is_default() const {
  const Appearance d;
  return board == d.board && background == d.background && sky == d.sky &&
         brick_length == d.brick_length && brick_height == d.brick_height &&
         joint_width == d.joint_width && to_light == d.to_light && ambient == d.ambient &&
         shadows == d.shadows && exposure == d.exposure && vignetting == d.vignetting &&
         blur_sigma == d.blur_sigma && gamma == d.gamma && colour == d.colour;
}

void Appearance::validate() const {
  check_range(brick_length, 0.05, 1.0, "brick_length", " m");
  check_range(brick_height, 0.03, 0.5, "brick_height", " m");
  check_range(joint_width, 0.001, 0.05, "joint_width", " m");
  if (!(joint_width < 0.5 * brick_height && joint_width < 0.5 * brick_length))
    throw ParamError("appearance.joint_width", "must be less than half a brick");
  if (!(to_light.allFinite() && std::abs(to_light.norm() - 1.0) < 1e-6))
    throw ParamError("appearance.to_light", "must be a unit vector");
  check_range(ambient, 0.0, 1.0, "ambient");
  check_range(exposure, 0.1, 10.0, "exposure");
  check_range(vignetting, 0.0, 0.8, "vignetting");
  check_range(blur_sigma, 0.0, 3.0, "blur_sigma", " px");
  check_range(gamma, 1.0, 3.0, "gamma");
}

}  // namespace l2s::sim
