#pragma once
// What the camera does to the light before the sensor noise: exposure gain
// and vignetting on the linear image, lens blur, then the gamma of the
// output encoding. Applied once to the clean image of a static scene, so it
// costs nothing per frame.

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/stereo_renderer.hpp>

#include <Eigen/Core>

namespace l2s::sim::detail {

/// In place; does nothing for the default appearance's response (gain 1, no
/// vignetting, no blur, gamma 1). `principal_point` [px] centres the vignetting.
void apply_camera_response(const Appearance& look, const Eigen::Vector2d& principal_point,
                           int threads, CleanImage* image);

}  // namespace l2s::sim::detail
