#pragma once
// How a simulated scene looks to the cameras: board and background
// materials, the light (a directional sun with optional hard shadows plus
// ambient light) and the camera's response (exposure, vignetting, lens blur,
// gamma, gray or colour). The defaults are the look of the paper suite: a
// bright matte board before a dark textured wall, soft light, no shadows,
// linear 8-bit gray.

#include <l2s/export.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace l2s::sim {

/// The board's front, back, edges and hole walls.
enum class BoardTexture {
  Matte,        ///< bright, fine low-contrast mottling (the paper suite's board)
  WoodGrain,    ///< plywood: streaks along the board's long side, warm colour
  LowContrast,  ///< matte, but its brightness close to the background's
  Speckle,      ///< a fine speckle print: dark dots of a few mm on white paper, for stereo matching
  NoisePrint,   ///< a coarse random-noise print: black and white blotches of 1-3 cm
  Chipboard,    ///< oriented strand board: overlapping wood flakes of a few cm at random angles
  Black,        ///< painted matte black: the board darker than most walls (inverted contrast)
  White,        ///< painted matte white, almost textureless (before a white wall: hardly any contrast)
  Logo,         ///< matte, with a printed logo and a text label beside one hole
  Sticker,      ///< matte, with a barcode sticker whose edge crosses one hole's rim
  Glossy,       ///< white laminate: the sun's mirror image is a highlight that can saturate, and cross a hole
};

/// The wall behind the board (the geometry puts it 0.5..6 m behind).
enum class Background {
  Textured,  ///< dark multi-scale texture (the paper suite's wall)
  Bricks,    ///< running-bond bricks with mortar joints: repetitive
  Tiles,     ///< square tiles with grout lines: repetitive in both directions
  Plain,     ///< painted wall, almost no texture
  White,     ///< painted white wall, almost no texture
};

/// What rays that hit nothing see.
enum class Sky {
  Uniform,   ///< flat bright gray (the paper suite)
  Daylight,  ///< brighter at the horizon, bluish towards the zenith
};

/// Names for files and the command line (board_texture_names() and
/// background_names() list them). Parsers throw ParamError naming `field`.
L2S_SIM_EXPORT const char* name_of(BoardTexture texture);
L2S_SIM_EXPORT const char* name_of(Background background);
L2S_SIM_EXPORT const char* name_of(Sky sky);
L2S_SIM_EXPORT BoardTexture board_texture_from_name(const std::string& name, const std::string& field);
L2S_SIM_EXPORT Background background_from_name(const std::string& name, const std::string& field);
L2S_SIM_EXPORT Sky sky_from_name(const std::string& name, const std::string& field);
L2S_SIM_EXPORT std::vector<std::string> board_texture_names();
L2S_SIM_EXPORT std::vector<std::string> background_names();

struct L2S_SIM_EXPORT Appearance {
  BoardTexture board = BoardTexture::Matte;
  Background background = Background::Textured;
  Sky sky = Sky::Uniform;
  double brick_length = 0.215;  ///< [m] brick length along the wall (tile side for Tiles), 0.05..1
  double brick_height = 0.065;  ///< [m] brick height (ignored by Tiles), 0.03..0.5
  double joint_width = 0.010;   ///< [m] mortar or grout joint, 0.001..0.05

  // Light: a sun at infinity plus uniform ambient light.
  Eigen::Vector3d to_light = Eigen::Vector3d(-1.0, 0.35, 0.6).normalized();  ///< unit, camera body frame, towards the sun
  double ambient = 0.35;  ///< share of the light that is ambient, 0..1 (1 - ambient is the sun's)
  bool shadows = false;   ///< hard shadows: a shadow ray towards the sun from every visible point

  // Camera response, applied to the linear image in this order.
  double exposure = 1.0;    ///< gain on the scene radiance, 0.1..10 (clips at white)
  double vignetting = 0.0;  ///< relative darkening at the image corners, 0..0.8
  double blur_sigma = 0.0;  ///< [px] Gaussian lens blur before the noise, 0..3
  double gamma = 1.0;       ///< encoding exponent: out = in^(1 / gamma), 1..3
  bool colour = false;      ///< 8-bit BGR images instead of 8-bit gray

  /// True when every field has its default (the renderer then keeps the
  /// paper suite's exact bytes).
  bool is_default() const;
  /// Throws ParamError naming the field ("appearance.<field>").
  void validate() const;
};

}  // namespace l2s::sim
