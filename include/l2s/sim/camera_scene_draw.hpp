#pragma once
// A random draw of the camera side of a scene for the randomised `scenes`
// experiment (issue 8): the stereo rig (resolution, field of view, baseline,
// and in about half the draws raw images from lenses with distortion and a
// slightly imperfect mount) and the look of the scene (board texture,
// background, sun and shadows, camera response). The lidar and scene
// geometry are drawn elsewhere; the two are composed into a SimulationConfig.

#include <l2s/export.hpp>
#include <l2s/sim/appearance.hpp>
#include <l2s/sim/stereo_rig.hpp>

#include <random>
#include <string>

namespace l2s::sim {

struct L2S_SIM_EXPORT CameraSceneDraw {
  StereoRig rig;          ///< 640x480..1920x1200, HFOV 40..100 deg, B 0.07..0.5 m; raw or ideal rectified
  Appearance appearance;  ///< every look, shadows in ~70 % of the draws
  /// What the look needs from the geometry (SceneLayout): the wall this far
  /// behind the board centre [m], 0.55..6 (bricks, tiles, plain or textured).
  double wall_gap = 3.0;
  /// Open space: no wall behind the board at all, only ground and sky. The
  /// geometry side must then build its scene without the wall.
  bool open_space = false;

  /// One line: rig, images, lens, look, e.g.
  /// "1280x960 66.0deg B=0.120m raw plumb_bob | wood on bricks 2.10m, shadows, colour".
  std::string summary() const;
};

/// Draws one camera side. Deterministic: the same generator state gives the
/// same draw on every platform (only the generator's raw 64-bit output is
/// used, no std distributions). Every draw passes StereoRig::validate and
/// Appearance::validate.
L2S_SIM_EXPORT CameraSceneDraw draw_camera_scene(std::mt19937_64& rng);

}  // namespace l2s::sim
