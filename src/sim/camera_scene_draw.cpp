// The ranges follow issue 8 ("Randomised scenes in the simulator") and what
// real rigs show: common sensor sizes, stereo lenses whose focal lengths
// differ by up to 1 %, pixels square to 0.5 %, principal points up to 2 % of
// the image off centre, right cameras turned by up to ~0.5 deg and shifted by
// up to 2 mm from their nominal mount, and distortion of the size lenses of
// that field of view have (typical_distortion, scaled 0.5..1.5).

#include <l2s/sim/camera_scene_draw.hpp>

#include <l2s/error.hpp>

#include "sim/draw_random.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace l2s::sim {
namespace {

using detail::chance;
using detail::pick;
using detail::uniform;

constexpr double kDeg = 3.141592653589793 / 180.0;

constexpr std::array<std::pair<int, int>, 11> kSensors{{{640, 480},   {752, 480},   {800, 600},
                                                        {1024, 768},  {1280, 720},  {1280, 960},
                                                        {1280, 1024}, {1440, 1080}, {1600, 1200},
                                                        {1920, 1080}, {1920, 1200}}};

/// A distortion of the drawn model around the typical size for the lens.
LensDistortion draw_distortion(std::mt19937_64& rng, DistortionModel model, double hfov, double scale) {
  LensDistortion d = typical_distortion(model, hfov);
  if (model == DistortionModel::PlumbBob) {
    d.coefficients[0] *= scale;
    d.coefficients[1] *= scale * scale;  // keeps 9 k1^2 < 20 k2: no fold
    d.coefficients[2] = uniform(rng, -1e-3, 1e-3);
    d.coefficients[3] = uniform(rng, -1e-3, 1e-3);
    d.coefficients[4] = uniform(rng, -0.01, 0.01) * scale;
  } else {
    for (int i = 0; i < 4; ++i) d.coefficients[static_cast<std::size_t>(i)] *= scale;
    d.coefficients[0] += uniform(rng, -0.02, 0.02);
  }
  return d;
}

/// Lens and mount flaws of a real pair with distortion `model`.
void draw_real_pair(std::mt19937_64& rng, DistortionModel model, StereoRig* rig) {
  const double scale = uniform(rng, 0.5, 1.5);
  for (std::size_t i = 0; i < 2; ++i) {
    CameraLens& lens = rig->lenses[i];
    lens.focal_scale = uniform(rng, 0.99, 1.01);
    lens.aspect = uniform(rng, 0.995, 1.005);
    lens.principal_offset = Eigen::Vector2d(uniform(rng, -0.02, 0.02) * rig->width,
                                            uniform(rng, -0.02, 0.02) * rig->height);
    // The two lenses of a pair are of one type; each has its own flaws.
    lens.distortion = draw_distortion(rng, model, rig->horizontal_fov, scale * uniform(rng, 0.9, 1.1));
  }
  for (int k = 0; k < 3; ++k) {
    rig->right_rotation[k] = uniform(rng, -0.005, 0.005);
    rig->right_offset[k] = uniform(rng, -0.002, 0.002);
  }
}

StereoRig draw_rig(std::mt19937_64& rng) {
  StereoRig rig;
  const auto& sensor = kSensors[static_cast<std::size_t>(uniform(rng, 0.0, kSensors.size()))];
  rig.width = sensor.first;
  rig.height = sensor.second;
  rig.horizontal_fov = uniform(rng, 40.0, 100.0) * kDeg;
  rig.baseline = 0.07 * std::exp(uniform(rng, 0.0, std::log(0.5 / 0.07)));  // log-uniform
  if (!chance(rng, 0.5)) return rig;  // an ideal rectified pair

  // Raw: fisheye-style lenses are likelier the wider the view.
  const double wide = (rig.horizontal_fov / kDeg - 40.0) / 60.0;
  const DistortionModel model = chance(rng, 0.15 + 0.45 * wide) ? DistortionModel::Equidistant
                                                                : DistortionModel::PlumbBob;
  // Redraw the rare combination that folds inside the image (deterministic:
  // the generator simply moves on).
  for (int attempt = 0;; ++attempt) {
    StereoRig raw = rig;
    draw_real_pair(rng, model, &raw);
    try {
      raw.validate();
      return raw;
    } catch (const ParamError&) {
      if (attempt == 20) throw;
    }
  }
}

Appearance draw_look(std::mt19937_64& rng) {
  Appearance look;
  look.board = std::array<BoardTexture, 3>{BoardTexture::Matte, BoardTexture::WoodGrain,
                                          BoardTexture::LowContrast}[pick(rng, std::array<double, 3>{0.35, 0.4, 0.25})];
  look.background = std::array<Background, 4>{Background::Textured, Background::Bricks, Background::Tiles,
                                              Background::Plain}[pick(rng, std::array<double, 4>{0.25, 0.4, 0.15, 0.2})];
  if (look.background == Background::Tiles) {
    look.brick_length = uniform(rng, 0.1, 0.3);
    look.joint_width = uniform(rng, 0.002, 0.006);
  } else {
    look.brick_length = uniform(rng, 0.19, 0.29);
    look.brick_height = uniform(rng, 0.05, 0.09);
    look.joint_width = uniform(rng, 0.008, 0.014);
  }
  look.sky = chance(rng, 0.7) ? Sky::Daylight : Sky::Uniform;
  // The sun behind the cameras' half-space, so the board's face is lit.
  const double azimuth = uniform(rng, -75.0, 75.0) * kDeg;
  const double elevation = uniform(rng, 15.0, 65.0) * kDeg;
  look.to_light = Eigen::Vector3d(-std::cos(elevation) * std::cos(azimuth),
                                  std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  look.shadows = chance(rng, 0.7);
  look.ambient = look.shadows ? uniform(rng, 0.2, 0.5) : uniform(rng, 0.3, 0.6);
  look.exposure = 0.6 * std::exp(uniform(rng, 0.0, std::log(1.6 / 0.6)));
  look.vignetting = uniform(rng, 0.0, 0.4);
  look.blur_sigma = uniform(rng, 0.0, 1.2);
  look.gamma = chance(rng, 0.4) ? 1.0 : uniform(rng, 1.8, 2.4);
  look.colour = chance(rng, 0.5);
  return look;
}

}  // namespace

CameraSceneDraw draw_camera_scene(std::mt19937_64& rng) {
  CameraSceneDraw draw;
  draw.rig = draw_rig(rng);
  draw.appearance = draw_look(rng);
  draw.open_space = chance(rng, 0.12);
  draw.wall_gap = uniform(rng, 0.55, 6.0);
  return draw;
}

std::string CameraSceneDraw::summary() const {
  char text[128];
  std::snprintf(text, sizeof text, "%dx%d %.1fdeg B=%.3fm ", rig.width, rig.height,
                rig.horizontal_fov / kDeg, rig.baseline);
  std::string line = text;
  line += rig.images() == ImageKind::Raw ? std::string("raw ") + name_of(rig.lenses[0].distortion.model)
                                         : std::string("rectified");
  if (rig.roll != 0.0) {
    std::snprintf(text, sizeof text, " rolled %.0fdeg", rig.roll / kDeg);
    line += text;
  }
  line += std::string(" | ") + name_of(appearance.board) + " on ";
  if (open_space) {
    line += "open space";
  } else {
    std::snprintf(text, sizeof text, "%s %.2fm", name_of(appearance.background), wall_gap);
    line += text;
  }
  if (appearance.shadows) line += ", shadows";
  if (appearance.colour) line += ", colour";
  return line;
}

}  // namespace l2s::sim
